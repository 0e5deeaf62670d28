#include "SceneOptions.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

#include "CommandLine.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Machine.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/FloatLimits.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/core/scene/SceneFields.h"

namespace microrelief {

namespace {

// The program's own flag over a georeferenced map's proportions (no scene field: the fit
// writes the height scale, SceneOptions.h).
constexpr const char* kExaggerationFlag = "--exaggeration";

// The flag of a field (a programming error when there is none).
std::string flag(std::string_view field) {
    std::string name = sceneFieldFlag(field);
    if (name.empty()) std::abort();
    return name;
}

// The field's line in --help, from its row (a programming error when there is none).
std::string help(std::string_view field) {
    const SceneField* row = findSceneField(field);
    if (!row || row->help.empty()) std::abort();
    return std::string(row->help);
}

}  // namespace

std::string flagName(const std::string& field) {
    const std::string name = sceneFieldFlag(field);
    return name.empty() ? field : name;
}

std::vector<double> parseNumberList(const std::string& flag, const std::string& text,
                                    std::size_t count, const std::string& what) {
    const auto invalid = [&] { throwBadInput(flag + " expects " + what + ", got '" + text + "'"); };
    std::vector<double> values;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, ',')) {
        std::size_t used = 0;
        double value = 0.0;
        try {
            value = std::stod(part, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != part.size() || !std::isfinite(value)) invalid();
        values.push_back(value);
    }
    if (values.size() != count || text.empty() || text.back() == ',') invalid();
    return values;
}

glm::dvec3 parseVectorFlag(const std::string& flag, const std::string& text, const char* expected,
                           double limit) {
    const std::vector<double> values = parseNumberList(flag, text, 3, expected);
    // Coordinates beyond the limit make exact hits impossible (core/scene/FloatLimits.h).
    for (double value : values) {
        if (std::abs(value) > limit) {
            throwBadInput(flag + " " + text + ": each component must lie within +-" +
                          exactNumber(limit) +
                          (limit == kMaxWorldPosition
                               ? " (world units; the renderer subtracts positions in double, "
                                 "which holds no more)"
                               : " (world units, the relief spans 1; the shader's float "
                                 "arithmetic holds no more)"));
        }
    }
    return {values[0], values[1], values[2]};
}

void parseSizeFlag(const std::string& text, int& width, int& height, int maxSide,
                   const std::string& limitReason, const std::string& flag) {
    std::istringstream in(text);
    char x = 0;
    long long w = 0, h = 0;
    std::string rest;
    // Digits only on both sides: "5x5junk", "5x5.5", "+5x5" and "5 x 5" are not sizes.
    const bool digits =
        !text.empty() && text.find_first_not_of("0123456789xX") == std::string::npos;
    if (!digits || !(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> rest) || w <= 0 ||
        h <= 0) {
        throwBadInput(flag + " expects WIDTHxHEIGHT with positive integers, got '" + text + "'");
    }
    if (w > maxSide || h > maxSide) {
        throwBadInput(flag + " " + text + " is larger than " + std::to_string(maxSide) + " x " +
                      std::to_string(maxSide) + (limitReason.empty() ? "" : ", " + limitReason));
    }
    width = static_cast<int>(w);
    height = static_cast<int>(h);
}

namespace {

template <class T>
std::string toChars(T value, int precision = -1) {
    char text[64];
    const auto end = precision < 0 ? std::to_chars(text, text + sizeof text, value).ptr
                                   : std::to_chars(text, text + sizeof text, value,
                                                   std::chars_format::general, precision)
                                         .ptr;
    return std::string(text, end);
}

// The shortest text that reads back as `value` both through std::stod (our vectors)
// and through CLI11 (strtold, then a cast: a second rounding that could in principle
// move a shortest text to the neighbouring value); else max_digits10 digits.
template <class T>
std::string exactText(T value) {
    const std::string shortest = toChars(value);
    const bool exact = static_cast<T>(std::strtold(shortest.c_str(), nullptr)) == value &&
                       static_cast<T>(std::strtod(shortest.c_str(), nullptr)) == value;
    return exact ? shortest : toChars(value, std::numeric_limits<T>::max_digits10);
}

std::string exactVector(const glm::vec3& v) {
    return exactText(v.x) + ',' + exactText(v.y) + ',' + exactText(v.z);
}

// A base size's numbers as its flag takes them, exactly: "0.3", or "0.5,0.35,0.4".
std::string sizeText(const BaseSize& size, const BaseShape& shape) {
    double numbers[3] = {};
    size.read(shape, numbers);
    std::string text;
    for (int i = 0; i < size.count; ++i) text += (i ? "," : "") + exactText(numbers[i]);
    return text;
}

}  // namespace

std::string exactNumber(double value) {
    return exactText(value);
}

std::string exactVector(const glm::dvec3& v) {
    return exactText(v.x) + ',' + exactText(v.y) + ',' + exactText(v.z);
}


// The flags' text seeded from the job's fields, written exactly, so that a parse that
// gives some flags changes those fields and keeps the rest (a camera file's row over the
// command line's scene); the defaults --help shows are these texts.
SceneFlags::SceneFlags(RenderJob& job, bool withAlbedo)
    : job_(job),
      withAlbedo_(withAlbedo),
      eye_(exactVector(job.camera.eye)),
      target_(exactVector(job.camera.target)),
      up_(exactVector(job.camera.up)),
      size_(std::to_string(job.width) + "x" + std::to_string(job.height)),
      method_(methodName(job.method.method)),
      view_(debugViewName(job.shading.view)),
      background_(exactVector(job.background)) {
    if (job.map.file) height_ = job.map.file->string();
    if (job.albedo.kind == AlbedoSource::Kind::File) albedo_ = job.albedo.file.string();
    if (job.albedo.kind == AlbedoSource::Kind::None) albedo_ = "none";
    base_ = baseName(job.base);
    for (const BaseSize& size : baseType(job.base).sizes)
        sizes_[size.field] = sizeText(size, job.base);
    interpolation_ = interpolationName(job.interpolation);
    if (job.tiles != glm::ivec2(1, 1))
        tile_ = std::to_string(job.tiles.x) + "," + std::to_string(job.tiles.y);
    animate_ = job.animation;
    if (!job.animation.empty()) time_ = job.time;
    if (job.shading.lightPosition) {
        lightPosition_ = exactVector(*job.shading.lightPosition);
    } else if (job.shading.lightDirection != ShadingOptions{}.lightDirection) {
        light_ = exactVector(job.shading.lightDirection);
    }
    shadows_ = shadowModeName(job.shading.shadows);
    if (!job.model.isIdentity()) {
        for (double value : job.model.rows()) model_ += (model_.empty() ? "" : ",") + exactNumber(value);
    }
}

// Each flag's name and --help line from its field's row (core/scene/SceneFields.h).
void SceneFlags::addMapAndCamera(CLI::App& app) {
    const auto option = [&](const char* field, auto& target) {
        return app.add_option(flag(field), target, help(field));
    };
    option("map.file", height_);
    if (withAlbedo_) option("albedo", albedo_);
    option("map.load.channel", job_.map.load.channel)->capture_default_str();
    app.add_flag(flag("map.load.normalize"), job_.map.load.normalize, help("map.load.normalize"));
    heightScaleOption_ = option("heightScale", job_.heightScale)->capture_default_str();
    if (fit_) {
        app.add_option(kExaggerationFlag, exaggeration_,
                       "A georeferenced map (GeoTIFF DEM, SRTM .hgt): its heights "
                       "times this over their true proportions (default 1)");
    }
    option("interpolation", interpolation_)->capture_default_str();
    std::string bases = help("base");
    for (const BaseType& type : baseTypes())
        bases += std::string(&type == &baseTypes().front() ? " " : ", ") + type.name + " (" +
                 type.summary + ")";
    baseOption_ = app.add_option(flag("base"), base_, bases)->capture_default_str();
    for (const std::string& field : baseSizeFields()) {
        // "Radius of the cylinder (default 0.3) or the sphere (default 0.5), world units"
        std::string text;
        int count = 1;
        for (const BaseType& type : baseTypes()) {
            for (const BaseSize& size : type.sizes) {
                if (size.field != field) continue;
                count = size.count;  // the same in every row (tests/batch: SceneFlags)
                if (text.empty())
                    text = std::string(size.label) + (size.count == 3 ? " x,y,z" : "") + " of the ";
                else
                    text += " or the ";
                text += std::string(type.name) + " (default " + sizeText(size, type.defaults) + ")";
            }
        }
        app.add_option(flag(field), sizes_[field], text + ", world units")
            ->type_name(count == 1 ? "FLOAT" : "X,Y,Z");
    }
    option("tiles", tile_);
    option("animation", animate_);
    option("time", time_);
    option("camera.eye", eye_)->capture_default_str();
    option("camera.target", target_)->capture_default_str();
    option("camera.up", up_)->capture_default_str();
    option("camera.fovyDegrees", job_.camera.fovyDegrees)->capture_default_str();
    option("size", size_)->capture_default_str();
    modelOption_ = option("model", model_);
}

void SceneFlags::addShading(CLI::App& app) {
    const auto option = [&](const char* field, auto& target) {
        return app.add_option(flag(field), target, help(field));
    };
    option("shading.lightDirection", light_);
    option("shading.lightPosition", lightPosition_);
    option("shading.shadows", shadows_)->capture_default_str();
    option("shading.lightSizeDegrees", job_.shading.lightSizeDegrees)->capture_default_str();
    option("method", method_)->capture_default_str();
    option("method.steps", job_.method.steps)->capture_default_str();
    option("method.pixelError", job_.method.pixelError)->capture_default_str();
    option("shading.view", view_)->capture_default_str();
    option("background", background_)->capture_default_str();
}

namespace {

// The --base flags into a shape: the named base's defaults, each size flag given only where
// that base has the size, each number positive and finite.
BaseShape parseBase(const std::string& name, const std::map<std::string, std::string>& sizes) {
    const BaseType& type = baseType(name);
    BaseShape shape = type.defaults;
    for (const auto& entry : sizes) {
        const std::string& field = entry.first;  // named, not bound: lambdas capture it
        const std::string& text = entry.second;
        if (text.empty()) continue;
        const std::string flagText = flag(field);
        const auto size = std::find_if(type.sizes.begin(), type.sizes.end(),
                                       [&](const BaseSize& s) { return s.field == field; });
        if (size == type.sizes.end()) throwBadInput(flagText + " does not apply to --base " + name);
        std::vector<double> numbers;
        if (size->count == 3) {
            const glm::dvec3 v = parseVectorFlag(flagText, text);
            numbers = {v.x, v.y, v.z};
        } else {
            numbers = parseNumberList(flagText, text, 1, "a number");
        }
        for (double number : numbers)
            if (!(number > 0.0)) throwBadInput(flagText + " must be a positive finite number");
        size->write(shape, numbers.data());
    }
    validateBaseShape(shape);
    return shape;
}

}  // namespace

glm::ivec2 parseTiles(const std::string& text) {
    const std::vector<double> counts =
        parseNumberList(flag("tiles"), text, 2, "two whole numbers N,M of at least 1");
    for (double n : counts) {
        if (n != std::floor(n) || n < 1.0 || n > kMaxTiles) {
            throwBadInput(flag("tiles") + " " + text +
                          ": each count must be a whole number from 1 to " +
                          std::to_string(kMaxTiles));
        }
    }
    return {static_cast<int>(counts[0]), static_cast<int>(counts[1])};
}

void SceneFlags::apply() {
    // The flags' text into the job's fields; each parse error names its flag. What is
    // wrong with the values then is the scene's to say, field by field (validateScene).
    if (!height_.empty()) job_.map.file = height_;
    if (withAlbedo_ && !albedo_.empty()) {
        job_.albedo = albedo_ == "none" ? AlbedoSource{AlbedoSource::Kind::None, {}}
                                        : AlbedoSource{AlbedoSource::Kind::File, albedo_};
    }
    job_.base = parseBase(base_, sizes_);
    job_.interpolation = parseInterpolation(interpolation_);
    if (!tile_.empty()) job_.tiles = parseTiles(tile_);
    if (!animate_.empty()) job_.animation = animate_;
    if (time_) {
        if (animate_.empty()) throwBadInput(flag("time") + " needs " + flag("animation") + " NAME");
        job_.time = *time_;
    }
    const char* const xyz = "three numbers x,y,z";
    job_.camera.eye = parseVectorFlag(flag("camera.eye"), eye_, xyz, kMaxWorldPosition);
    job_.camera.target = parseVectorFlag(flag("camera.target"), target_, xyz, kMaxWorldPosition);
    job_.camera.up = parseVectorFlag(flag("camera.up"), up_);
    // The lights are checked in double, before they are stored in float (core/scene/Scene.h).
    if (!light_.empty()) {
        const glm::dvec3 light = parseVectorFlag(flag("shading.lightDirection"), light_);
        std::vector<FieldError> errors;
        checkDirection(errors, "shading.lightDirection", light);
        throwIfInvalid(errors);
        job_.shading.lightDirection = glm::vec3(light);
    }
    if (!lightPosition_.empty()) {
        if (!light_.empty())
            throwBadInput(flag("shading.lightDirection") + " and " + flag("shading.lightPosition") +
                          " are two lights: give one");
        const glm::dvec3 position =
            parseVectorFlag(flag("shading.lightPosition"), lightPosition_, xyz, kMaxWorldPosition);
        std::vector<FieldError> errors;
        checkPoint(errors, "shading.lightPosition", position);
        throwIfInvalid(errors);
        job_.shading.lightPosition = position;
    }
    job_.shading.shadows = parseShadowMode(shadows_);
    // Any side here; the scene states the limits, sides and pixels, in one message.
    parseSizeFlag(size_, job_.width, job_.height, 1 << 30);
    job_.shading.view = parseDebugView(view_);
    job_.method.method = parseMethod(method_);
    if (job_.method.steps >= 1 && job_.method.steps <= 65536) job_.method.setSteps(job_.method.steps);
    job_.background =
        glm::vec3(parseVectorFlag(flag("background"), background_, "three numbers r,g,b"));
    if (!model_.empty()) {
        const std::vector<double> rows = parseNumberList(
            flag("model"), model_, 12, "12 numbers: a 3 x 4 matrix in rows, comma-separated");
        std::array<double, 12> m{};
        std::copy(rows.begin(), rows.end(), m.begin());
        job_.model = ModelTransform::fromRows(m);
    }
    if (fit_) {
        // Given here or by the scene this parse goes over (a camera file's row over the
        // command line): kept over a georeferenced map's own.
        fit_->keepHeightScale |= heightScaleOption_->count() > 0;
        fit_->keepModel |= modelOption_->count() > 0;
        fit_->keepBase |= baseOption_->count() > 0;
        if (exaggeration_) {
            if (!(*exaggeration_ > 0.0) || !std::isfinite(*exaggeration_))
                throwBadInput(std::string(kExaggerationFlag) + " must be a positive finite number");
            if (heightScaleOption_->count() > 0)
                throwBadInput(std::string(kExaggerationFlag) +
                              " scales a georeferenced map's true heights and " +
                              flag("heightScale") + " sets the height scale outright: give one");
            fit_->exaggeration = *exaggeration_;
            fit_->keepHeightScale = false;
        }
    }
    throwIfInvalid(validateScene(job_, job_));
}

RenderJob sceneOverMap(const RenderJob& job, const GeoreferenceFit& fit, int width, int height,
                       const std::optional<Georeference>& geo, const std::string& source) {
    if (!geo) return job;
    RenderJob fitted = job;
    fitToGeoreference(fitted, width, height, *geo, fit);
    // A height scale the fit made (no --height-scale given) is the file's and the
    // exaggeration's to answer for, not a flag's.
    if (!fit.keepHeightScale && !(fitted.heightScale > 0.0f && std::isfinite(fitted.heightScale)))
        throwBadInput(source + ": its true proportions" +
                      (fit.exaggeration != 1.0 ? " at " + std::string(kExaggerationFlag) + " " +
                                                     formatNumber(fit.exaggeration, 6)
                                               : std::string()) +
                      " give a height scale of " + formatNumber(fitted.heightScale, 6) +
                      ", which no relief can have (heights " + formatNumber(geo->lowestMetres, 9) +
                      " to " + formatNumber(geo->highestMetres, 9) + " m over samples of " +
                      formatNumber(geo->sampleWidthMetres, 6) + " x " +
                      formatNumber(geo->sampleHeightMetres, 6) + " m)");
    throwIfInvalid(validateScene(fitted, fitted));
    return fitted;
}

std::string exaggerationUnused(const std::string& source, const GeoreferenceFit& fit,
                               const std::optional<Georeference>& geo) {
    if (geo || fit.exaggeration == 1.0) return {};
    return std::string(kExaggerationFlag) + ": " + source +
           " has no georeference (a GeoTIFF grid, an .hgt tile); it is drawn at --height-scale";
}

std::string georeferenceSummary(const std::string& file, const Georeference& geo,
                                const RenderJob& fitted, const GeoreferenceFit& fit) {
    std::string line = file + ": " +
                       (geo.crs.empty()        ? "no coordinate system (the grid taken as metres)"
                        : geo.crs == "unknown" ? "an unnamed coordinate system"
                                               : geo.crs) +
                       ", samples " + formatNumber(geo.sampleWidthMetres, 4) + " x " +
                       formatNumber(geo.sampleHeightMetres, 4) + " m, heights " +
                       formatNumber(geo.lowestMetres, 9) + " to " +
                       formatNumber(geo.highestMetres, 9) + " m";
    if (geo.nodataSamples > 0)
        line += " (" + std::to_string(geo.nodataSamples) + " nodata samples filled with " +
                formatNumber(geo.lowestMetres, 9) + " m)";
    const std::string scale = formatNumber(fitted.heightScale, 4);
    if (fit.keepHeightScale)
        line += "; height scale " + scale + " as given";
    else if (!(geo.highestMetres > geo.lowestMetres))
        line += "; flat, height scale " + scale + " as it was";
    else
        line += std::string("; drawn at its true proportions") +
                (fit.exaggeration != 1.0
                     ? " exaggerated " + formatNumber(fit.exaggeration, 6) + " times"
                     : "") +
                " (height scale " + scale + ")";
    if (geo.global && fitted.base.curved() && !fit.keepBase) line += " on the ellipsoid";
    if (fit.keepModel && !fitted.base.curved() && !squareSamples(geo))
        line += "; --model as given: its samples are not stretched to their ground ratio";
    return line;
}

std::string shellQuote(const std::string& text) {
    const bool plain = !text.empty() && text.find_first_not_of(
                                            "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                            "0123456789_-+=.,/:@%") == std::string::npos;
    if (plain) return text;
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::vector<NamedFile> filesRead(const ReliefDesc& relief, const std::string& where) {
    std::vector<NamedFile> files{{heightMapPath(relief), where + flagName("map.file")}};
    if (const std::optional<std::filesystem::path> albedo = albedoPath(relief))
        files.push_back({*albedo, where + flagName("albedo")});
    return files;
}

std::string renderCommandLine(const SceneOptions& o, const std::string& program) {
    const RenderJob& job = o.job;
    std::string line = program;
    // Each field's flag by name (core/scene/SceneFields.h); `value` quoted, or after "=" where a
    // leading minus must not read as a flag in any parser.
    const auto add = [&](const char* field, const std::string& value) {
        line += std::string(" ") + flag(field) + (value.empty() ? "" : " " + shellQuote(value));
    };
    const auto assign = [&](const char* field, const std::string& value) {
        line += std::string(" ") + flag(field) + "=" + value;
    };
    if (job.map.file) add("map.file", job.map.file->string());
    if (job.albedo.kind == AlbedoSource::Kind::File) add("albedo", job.albedo.file.string());
    if (job.albedo.kind == AlbedoSource::Kind::None) add("albedo", "none");
    if (job.map.load.channel != 0) add("map.load.channel", std::to_string(job.map.load.channel));
    if (job.map.load.normalize) add("map.load.normalize", "");
    add("heightScale", exactText(job.heightScale));
    if (job.interpolation != Interpolation::Bilinear)
        add("interpolation", interpolationName(job.interpolation));
    if (job.tiles != glm::ivec2(1, 1))
        add("tiles", std::to_string(job.tiles.x) + "," + std::to_string(job.tiles.y));
    const BaseType& base = baseType(job.base);
    // The default base goes without saying, but where it was chosen over a georeferenced
    // map's own (a global grid's ellipsoid).
    if (&base != &baseType(BaseShape{}) || o.georeference.keepBase) {
        add("base", base.name);
        for (const BaseSize& size : base.sizes) {
            if (size.count == 1)
                add(size.field, sizeText(size, job.base));
            else
                assign(size.field, sizeText(size, job.base));
        }
    }
    if (!job.animation.empty()) {
        add("animation", job.animation);
        assign("time", exactNumber(job.time));
    }
    // "=" keeps a leading minus from reading as a flag in any parser.
    assign("camera.eye", exactVector(job.camera.eye));
    assign("camera.target", exactVector(job.camera.target));
    assign("camera.up", exactVector(job.camera.up));
    add("camera.fovyDegrees", exactText(job.camera.fovyDegrees));
    add("size", std::to_string(job.width) + "x" + std::to_string(job.height));
    if (!job.model.isIdentity()) {
        std::string rows;
        for (double value : job.model.rows())
            rows += (rows.empty() ? "" : ",") + exactNumber(value);
        assign("model", rows);
    }
    if (job.shading.lightPosition) {
        assign("shading.lightPosition", exactVector(*job.shading.lightPosition));
    } else {
        assign("shading.lightDirection", exactVector(job.shading.lightDirection));
    }
    if (job.shading.shadows != ShadowMode::Off)
        add("shading.shadows", shadowModeName(job.shading.shadows));
    // Whenever it is not the default, shadows or not: a camera-file row that turns soft
    // shadows on keeps the command line's light size.
    if (job.shading.shadows == ShadowMode::Soft ||
        job.shading.lightSizeDegrees != ShadingOptions{}.lightSizeDegrees)
        add("shading.lightSizeDegrees", exactText(job.shading.lightSizeDegrees));
    add("method", methodName(job.method.method));
    const MethodSettings defaults;
    if (job.method.steps != defaults.steps) add("method.steps", std::to_string(job.method.steps));
    if (job.method.pixelError != defaults.pixelError)
        add("method.pixelError", exactText(job.method.pixelError));
    add("shading.view", debugViewName(job.shading.view));
    // Only when changed: the command stays short, and runs on renderers without the flag.
    if (job.background != RenderJob{}.background) add("background", exactVector(job.background));
    return line;
}

CLI::Option* addMemoryFlag(CLI::App& app, std::size_t& mib, const std::string& drawn) {
    return app
        .add_option("--memory", mib,
                    "GPU memory for the pages of a map larger than the GL's textures, MiB "
                    "(such a map is read through pages, " +
                        drawn + ")")
        ->capture_default_str()
        ->check(wholeNumberIn(1, std::size_t{1} << 20));
}

void allowPagedMaps(HeightMapLoadOptions& load) {
    load.maxSide = kMaxPagedHeightMapSide;
    load.maxSamples = availableMemoryBytes() / kPagedBytesPerSample;
}

}  // namespace microrelief
