#include "SceneOptions.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
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

// Each binding's text seeded from the job's field, written exactly, so that a parse that
// gives some flags changes those fields and keeps the rest (a camera file's row over the
// command line's scene); the defaults --help shows are these texts.
SceneFlags::SceneFlags(RenderJob& job, bool withAlbedo) : job_(job), withAlbedo_(withAlbedo) {
    // A row without its binding, or a binding without its row, is a programming error.
    static const bool complete = [] {
        const std::vector<std::string> gaps = sceneBindingGaps(sceneFieldTable(), sceneBindings());
        for (const std::string& gap : gaps) std::fprintf(stderr, "scene flags: %s\n", gap.c_str());
        return gaps.empty();
    }();
    if (!complete) std::abort();
    for (const SceneBinding& binding : sceneBindings()) {
        FlagSlot& slot = slots_[binding.path];
        if (binding.seed) binding.seed(job, slot);
    }
}

// Each flag's name and --help line from its field's row (core/scene/SceneFields.h), how it
// is read from its binding (SceneBindings.h).
void SceneFlags::add(CLI::App& app, FlagGroup group) {
    for (const SceneBinding& binding : sceneBindings()) {
        if (binding.group != group || (binding.albedoOnly && !withAlbedo_)) continue;
        FlagSlot& slot = slots_.at(binding.path);
        slot.option = binding.add(app, job_, slot, flag(binding.path), help(binding.path));
        // The program's own flag over a georeferenced map's height scale, after it.
        if (binding.path == "heightScale" && fit_) {
            app.add_option(kExaggerationFlag, exaggeration_,
                           "A georeferenced map (GeoTIFF DEM, SRTM .hgt): its heights "
                           "times this over their true proportions (default 1)");
        }
    }
}

void SceneFlags::addMapAndCamera(CLI::App& app) {
    add(app, FlagGroup::MapAndCamera);
}

void SceneFlags::addShading(CLI::App& app) {
    add(app, FlagGroup::Shading);
}

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
    // The flags' text into the job's fields, in the bindings' order (but those read after
    // another); each parse error names its flag. What is wrong with the values then is the scene's to say, field by field
    // (validateScene).
    const std::span<const SceneBinding> bindings = sceneBindings();
    // A binding, then those read after it (SceneBinding::parsedAfter).
    const std::function<void(const SceneBinding&)> read = [&](const SceneBinding& binding) {
        if (binding.apply && !(binding.albedoOnly && !withAlbedo_))
            binding.apply(job_, slots_.at(binding.path), slots_);
        for (const SceneBinding& next : bindings)
            if (next.parsedAfter == binding.path) read(next);
    };
    for (const SceneBinding& binding : bindings)
        if (binding.parsedAfter.empty()) read(binding);
    if (fit_) {
        // Given here or by the scene this parse goes over (a camera file's row over the
        // command line): kept over a georeferenced map's own.
        for (const SceneBinding& binding : sceneBindings())
            if (binding.keep) fit_->*binding.keep |= slots_.at(binding.path).option->count() > 0;
        if (exaggeration_) {
            if (!(*exaggeration_ > 0.0) || !std::isfinite(*exaggeration_))
                throwBadInput(std::string(kExaggerationFlag) + " must be a positive finite number");
            if (slots_.at("heightScale").option->count() > 0)
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
    if (relief.onMesh && relief.mesh.file)
        files.push_back({*relief.mesh.file, where + flagName("mesh.file")});
    return files;
}

std::string renderCommandLine(const SceneOptions& o, const std::string& program) {
    // Each field's binding writes its flag, named by its row (core/scene/SceneFields.h), where
    // the field is not left to its default; one echoed before another goes there.
    CommandEcho out{program};
    const std::span<const SceneBinding> bindings = sceneBindings();
    for (const SceneBinding& binding : bindings) {
        for (const SceneBinding& early : bindings)
            if (early.echoedBefore == binding.path) early.echo(o.job, o.georeference, out);
        if (binding.echoedBefore.empty()) binding.echo(o.job, o.georeference, out);
    }
    return out.line;
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
