#include "SceneOptions.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/render/AnimatedHeights.h"
#include "microrelief/render/FloatLimits.h"

namespace microrelief {

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

glm::dvec3 parseVectorFlag(const std::string& flag, const std::string& text) {
    const std::vector<double> values = parseNumberList(flag, text, 3, "three numbers x,y,z");
    // The shader gets these as floats; camera coordinates beyond the limit also make
    // exact hits impossible (render/FloatLimits.h).
    for (double value : values) {
        if (std::abs(value) > kMaxWorldCoordinate) {
            throwBadInput(flag + " " + text + ": each component must lie within +-" +
                          exactNumber(kMaxWorldCoordinate) +
                          " (world units, the relief spans 1; the shader's float "
                          "arithmetic holds no more)");
        }
    }
    return {values[0], values[1], values[2]};
}

void parseSizeFlag(const std::string& text, int& width, int& height, int maxSide,
                   const std::string& limitReason) {
    std::istringstream in(text);
    char x = 0;
    long long w = 0, h = 0;
    std::string rest;
    // Digits only on both sides: "5x5junk", "5x5.5", "+5x5" and "5 x 5" are not sizes.
    const bool digits =
        !text.empty() && text.find_first_not_of("0123456789xX") == std::string::npos;
    if (!digits || !(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> rest) || w <= 0 ||
        h <= 0) {
        throwBadInput("--size expects WIDTHxHEIGHT with positive integers, got '" + text + "'");
    }
    if (w > maxSide || h > maxSide) {
        throwBadInput("--size " + text + " is larger than " + std::to_string(maxSide) + " x " +
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

std::string vectorText(const glm::dvec3& v) {
    std::ostringstream out;
    out << v.x << ',' << v.y << ',' << v.z;
    return out.str();
}

std::string exactVector(const glm::vec3& v) {
    return exactText(v.x) + ',' + exactText(v.y) + ',' + exactText(v.z);
}

}  // namespace

std::string exactNumber(double value) {
    return exactText(value);
}

std::string exactVector(const glm::dvec3& v) {
    return exactText(v.x) + ',' + exactText(v.y) + ',' + exactText(v.z);
}

namespace {

// A direction the shader normalises in float: not zero, and not so short that its
// squared length underflows (render/FloatLimits.h).
void checkDirection(const std::string& flag, const std::string& text, const glm::dvec3& v) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (largest == 0.0) throwBadInput(flag + " must not be zero");
    if (largest < kMinDirectionComponent) {
        throwBadInput(flag + " " + text + ": its largest component must be at least " +
                      exactNumber(kMinDirectionComponent) + " (the shader normalises it in float)");
    }
}

}  // namespace

SceneFlags::SceneFlags(std::optional<std::filesystem::path>& heightFile, HeightMapLoadOptions& load,
                       RenderJob& job)
    : heightFile_(heightFile),
      load_(load),
      job_(job),
      eye_(vectorText(job.camera.eye)),
      target_(vectorText(job.camera.target)),
      up_(vectorText(job.camera.up)),
      size_(std::to_string(job.width) + "x" + std::to_string(job.height)),
      method_(methodName(job.method.method)),
      view_(debugViewName(job.shading.view)),
      background_(vectorText(glm::dvec3(job.background))) {}

void SceneFlags::addMapAndCamera(CLI::App& app) {
    app.add_option("--height", height_,
                   "Height map image (any format OpenImageIO reads); default: the bundled map");
    if (albedoFile_) {
        app.add_option("--albedo", albedo_,
                       "The map's colours: an image over its (u, v), any size (sRGB unless float), "
                       "or none; default: the bundled map's own with the bundled map");
    }
    app.add_option("--channel", load_.channel, "Image channel holding the heights")
        ->capture_default_str();
    app.add_flag("--normalize", load_.normalize, "Map the map's [min, max] to [0, 1]");
    app.add_option("--height-scale", job_.heightScale,
                   "World height of map value 1 (the map spans 1 unit)")
        ->capture_default_str();
    app.add_option("--interpolation", interpolation_,
                   "The last level: bilinear, or biquadratic (the quadratic B-spline of the "
                   "samples: smooth)")
        ->capture_default_str();
    app.add_option("--base", base_,
                   "Base surface the map is laid over: plane, cylinder (axis y), ellipsoid or "
                   "sphere (u wraps around the y axis)")
        ->capture_default_str();
    app.add_option("--radius", radius_,
                   "Cylinder radius (default 0.3) or sphere radius (default 0.5), world units");
    app.add_option("--length", length_, "Cylinder length along y (default 1), world units");
    app.add_option("--radii", radii_, "Ellipsoid radii A,B,C along x, y, z (default 0.5,0.5,0.5)");
    app.add_option(
        "--tile", tile_,
        "Repeat the map N,M times across the base (N around a curved base), as the N x M "
        "larger image made by repeating it (default 1,1)");
    app.add_option("--animate", animate_,
                   "An animated relief over the map's grid, evaluated on the GPU: waves, ripples, "
                   "or flood (the map under rising and falling water)");
    app.add_option("--time", time_, "With --animate: the moment drawn, seconds (default 0)");
    app.add_option("--eye", eye_, "Camera position x,y,z (world, y up)")->capture_default_str();
    app.add_option("--target", target_, "Point the camera looks at, x,y,z")->capture_default_str();
    app.add_option("--up", up_, "Camera up direction x,y,z")->capture_default_str();
    app.add_option("--fovy", job_.camera.fovyDegrees, "Vertical field of view in degrees")
        ->capture_default_str();
    app.add_option("--size", size_, "Picture size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--model", model_,
                   "Where the relief sits in the world: a 3 x 4 affine matrix, 12 numbers in rows "
                   "(m00,m01,m02,tx,m10,...,tz); default: the identity");
}

void SceneFlags::addShading(CLI::App& app) {
    app.add_option("--light", light_,
                   "Direction towards the light x,y,z (default -0.45,0.8,-0.35)");
    app.add_option("--light-position", lightPosition_,
                   "A point light at x,y,z (world) instead of the directional light");
    app.add_option("--shadows", shadows_,
                   "Self-shadows: off, hard (exact: a second trace towards the light) or soft (an "
                   "estimate for a round light of --light-size); multilevel and maxmip")
        ->capture_default_str();
    app.add_option("--light-size", job_.shading.lightSizeDegrees,
                   "Soft shadows: the light's angular diameter in degrees (the sun's is 0.53)")
        ->capture_default_str();
    app.add_option(
           "--method", method_,
           "How rays are traced: multilevel (the paper's method, exact), or a peer for comparison: "
           "normal, offset, steep, pom, relief, maxmip")
        ->capture_default_str();
    app.add_option(
           "--steps", job_.method.steps,
           "Peers' quality knob: steep layers, pom samples at grazing angles, relief linear steps")
        ->capture_default_str();
    app.add_option(
           "--pixel-error", job_.method.pixelError,
           "multilevel: stop at pyramid levels whose windows project to less than this many pixels "
           "(0: exact)")
        ->capture_default_str();
    app.add_option(
           "--view", view_,
           "What the picture shows: shaded, or a debug view of the method: iterations (segments "
           "visited, heat map), level (pyramid level where the ray stopped), normal, depth, "
           "position")
        ->capture_default_str();
    app.add_option("--background", background_, "Background colour r,g,b (linear, 0 to 1)")
        ->capture_default_str();
}

namespace {

// The --base flags into a shape: each size flag only where its base has that size, each
// size positive and finite.
BaseShape parseBase(const std::string& name, const std::optional<double>& radius,
                    const std::optional<double>& length, const std::string& radii) {
    const BaseKind kind = parseBaseKind(name);
    const bool sphere = name == "sphere";
    const auto refuse = [&](const char* flag) {
        throwBadInput(std::string(flag) + " does not apply to --base " + name);
    };
    for (const auto& [flag, value] :
         {std::pair{"--radius", radius}, std::pair{"--length", length}}) {
        if (value && !(*value > 0.0 && std::isfinite(*value)))
            throwBadInput(std::string(flag) + " must be a positive finite number");
    }
    BaseShape shape;
    switch (kind) {
        case BaseKind::Plane:
            if (radius) refuse("--radius");
            if (length) refuse("--length");
            if (!radii.empty()) refuse("--radii");
            return shape;
        case BaseKind::Cylinder:
            if (!radii.empty()) refuse("--radii");
            shape = BaseShape::cylinder(radius.value_or(0.3), length.value_or(1.0));
            break;
        case BaseKind::Ellipsoid:
            if (length) refuse("--length");
            if (sphere) {
                if (!radii.empty()) refuse("--radii");
                shape = BaseShape::sphere(radius.value_or(0.5));
            } else {
                if (radius) refuse("--radius");
                shape = BaseShape::ellipsoid(radii.empty() ? glm::dvec3(0.5)
                                                           : parseVectorFlag("--radii", radii));
            }
            break;
    }
    validateBaseShape(shape);
    return shape;
}

}  // namespace

glm::ivec2 parseTiles(const std::string& text) {
    const std::vector<double> counts =
        parseNumberList("--tile", text, 2, "two whole numbers N,M of at least 1");
    for (double n : counts) {
        if (n != std::floor(n) || n < 1.0 || n > kMaxTiles) {
            throwBadInput("--tile " + text + ": each count must be a whole number from 1 to " +
                          std::to_string(kMaxTiles));
        }
    }
    return {static_cast<int>(counts[0]), static_cast<int>(counts[1])};
}

void SceneFlags::apply() {
    if (!height_.empty()) heightFile_ = height_;
    if (albedoFile_ && !albedo_.empty()) {
        *noAlbedo_ = albedo_ == "none";
        *albedoFile_ = *noAlbedo_ ? std::nullopt : std::optional<std::filesystem::path>(albedo_);
    }
    job_.base = parseBase(base_, radius_, length_, radii_);
    job_.interpolation = parseInterpolation(interpolation_);
    if (!tile_.empty()) job_.tiles = parseTiles(tile_);
    if (!animate_.empty()) {
        AnimatedHeights::checkName(animate_);
        if (job_.tiles != glm::ivec2(1, 1))
            throwBadInput("--animate and --tile: an animated height field does not tile");
        job_.animation = animate_;
    }
    if (time_) {
        if (animate_.empty()) throwBadInput("--time needs --animate NAME");
        if (!(std::abs(*time_) <= kMaxAnimationSeconds))
            throwBadInput("--time must be a number of seconds within +-1e9, got " +
                          exactNumber(*time_));
        job_.time = *time_;
    }
    job_.camera.eye = parseVectorFlag("--eye", eye_);
    job_.camera.target = parseVectorFlag("--target", target_);
    job_.camera.up = parseVectorFlag("--up", up_);
    checkDirection("--up", up_, job_.camera.up);
    if (!light_.empty()) {
        const glm::dvec3 light = parseVectorFlag("--light", light_);
        checkDirection("--light", light_, light);
        job_.shading.lightDirection = glm::vec3(light);
    }
    if (!lightPosition_.empty()) {
        if (!light_.empty()) throwBadInput("--light and --light-position are two lights: give one");
        job_.shading.lightPosition = glm::vec3(parseVectorFlag("--light-position", lightPosition_));
    }
    job_.shading.shadows = parseShadowMode(shadows_);
    if (!(job_.shading.lightSizeDegrees > 0.0f && job_.shading.lightSizeDegrees < 90.0f))
        throwBadInput("--light-size must lie strictly between 0 and 90 degrees");
    // Any side here; checkPictureSize states the limits, sides and pixels, in one message.
    parseSizeFlag(size_, job_.width, job_.height, 1 << 30);
    checkPictureSize(job_.width, job_.height);
    job_.shading.view = parseDebugView(view_);
    job_.method.method = parseMethod(method_);
    checkMethodSupportsBase(job_.method.method, job_.base);
    checkMethodSupportsTiles(job_.method.method, job_.tiles);
    if (job_.shading.shadows != ShadowMode::Off && !methodTracesTheSolid(job_.method.method)) {
        throwBadInput(std::string("--shadows ") + shadowModeName(job_.shading.shadows) +
                      " takes the exact methods, multilevel and maxmip (not --method " +
                      methodName(job_.method.method) + ")");
    }
    if (job_.method.steps < 1 || job_.method.steps > 65536)
        throwBadInput("--steps must lie in 1..65536");
    job_.method.setSteps(job_.method.steps);
    if (!(job_.method.pixelError >= 0.0f) || !std::isfinite(job_.method.pixelError)) {
        throwBadInput("--pixel-error must be a number >= 0");
    }
    job_.background = glm::vec3(parseVectorFlag("--background", background_));
    if (glm::any(glm::lessThan(job_.background, glm::vec3(0.0f))))
        throwBadInput("--background must be >= 0");
    if (!(job_.heightScale > 0.0f) || !std::isfinite(job_.heightScale)) {
        throwBadInput("--height-scale must be a positive number");
    }
    if (!(job_.camera.fovyDegrees > 0.0 && job_.camera.fovyDegrees < 180.0)) {
        throwBadInput("--fovy must lie strictly between 0 and 180 degrees");
    }
    if (load_.channel < 0) throwBadInput("--channel must be >= 0");
    if (!model_.empty()) {
        const std::vector<double> rows = parseNumberList(
            "--model", model_, 12, "12 numbers: a 3 x 4 matrix in rows, comma-separated");
        std::array<double, 12> m{};
        std::copy(rows.begin(), rows.end(), m.begin());
        job_.model = ModelTransform::fromRows(m);
    }
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

std::optional<std::filesystem::path> albedoPath(const SceneOptions& options) {
    if (options.noAlbedo) return std::nullopt;
    if (options.albedoFile) return options.albedoFile;
    // The bundled map's colours go with its stones: not with a field that replaces them.
    const std::string& animation = options.job.animation;
    if (!options.heightFile && (animation.empty() || AnimatedHeights::showsTheMap(animation)))
        return defaultAlbedoPath();
    return std::nullopt;
}

std::string renderCommandLine(const SceneOptions& o, const std::string& program) {
    const RenderJob& job = o.job;
    std::string line = program;
    const auto flag = [&](const std::string& name, const std::string& value) {
        line += " " + name + (value.empty() ? "" : " " + shellQuote(value));
    };
    if (o.heightFile) flag("--height", o.heightFile->string());
    if (o.albedoFile) flag("--albedo", o.albedoFile->string());
    if (o.noAlbedo) flag("--albedo", "none");
    if (o.load.channel != 0) flag("--channel", std::to_string(o.load.channel));
    if (o.load.normalize) flag("--normalize", "");
    flag("--height-scale", exactText(job.heightScale));
    if (job.interpolation != Interpolation::Bilinear)
        flag("--interpolation", interpolationName(job.interpolation));
    if (job.tiles != glm::ivec2(1, 1))
        flag("--tile", std::to_string(job.tiles.x) + "," + std::to_string(job.tiles.y));
    const std::string base = baseName(job.base);
    if (job.base.kind == BaseKind::Cylinder) {
        flag("--base", base);
        flag("--radius", exactText(job.base.radius));
        flag("--length", exactText(job.base.length));
    } else if (base == "sphere") {
        flag("--base", base);
        flag("--radius", exactText(job.base.radii.x));
    } else if (job.base.kind == BaseKind::Ellipsoid) {
        flag("--base", base);
        line += " --radii=" + exactVector(job.base.radii);
    }
    if (!job.animation.empty()) {
        flag("--animate", job.animation);
        line += " --time=" + exactNumber(job.time);
    }
    // "=" keeps a leading minus from reading as a flag in any parser.
    line += " --eye=" + exactVector(job.camera.eye);
    line += " --target=" + exactVector(job.camera.target);
    line += " --up=" + exactVector(job.camera.up);
    flag("--fovy", exactText(job.camera.fovyDegrees));
    flag("--size", std::to_string(job.width) + "x" + std::to_string(job.height));
    if (!job.model.isIdentity()) {
        std::string rows;
        for (double value : job.model.rows())
            rows += (rows.empty() ? "" : ",") + exactNumber(value);
        line += " --model=" + rows;
    }
    if (job.shading.lightPosition) {
        line += " --light-position=" + exactVector(*job.shading.lightPosition);
    } else {
        line += " --light=" + exactVector(job.shading.lightDirection);
    }
    if (job.shading.shadows != ShadowMode::Off)
        flag("--shadows", shadowModeName(job.shading.shadows));
    // Whenever it is not the default, shadows or not: a camera-file row that turns soft
    // shadows on keeps the command line's light size.
    if (job.shading.shadows == ShadowMode::Soft ||
        job.shading.lightSizeDegrees != ShadingOptions{}.lightSizeDegrees)
        flag("--light-size", exactText(job.shading.lightSizeDegrees));
    flag("--method", methodName(job.method.method));
    const MethodSettings defaults;
    if (job.method.steps != defaults.steps) flag("--steps", std::to_string(job.method.steps));
    if (job.method.pixelError != defaults.pixelError)
        flag("--pixel-error", exactText(job.method.pixelError));
    flag("--view", debugViewName(job.shading.view));
    // Only when changed: the command stays short, and runs on renderers without the flag.
    if (job.background != RenderJob{}.background) flag("--background", exactVector(job.background));
    return line;
}

}  // namespace microrelief
