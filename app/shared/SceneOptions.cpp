#include "SceneOptions.h"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <vector>

#include "core/Error.h"

namespace microrelief {

glm::dvec3 parseVectorFlag(const std::string& flag, const std::string& text) {
    const auto invalid = [&] { throwBadInput(flag + " expects three numbers x,y,z, got '" + text + "'"); };
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
    if (values.size() != 3 || text.back() == ',') invalid();
    return {values[0], values[1], values[2]};
}

void parseSizeFlag(const std::string& text, int& width, int& height) {
    std::istringstream in(text);
    char x = 0;
    long w = 0, h = 0;
    std::string rest;
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> rest) || w <= 0 || h <= 0 || w > 65536 ||
        h > 65536) {
        throwBadInput("--size expects WIDTHxHEIGHT with positive integers, got '" + text + "'");
    }
    width = static_cast<int>(w);
    height = static_cast<int>(h);
}

namespace {

template <class T>
std::string toChars(T value, int precision = -1) {
    char text[64];
    const auto end = precision < 0 ? std::to_chars(text, text + sizeof text, value).ptr
                                   : std::to_chars(text, text + sizeof text, value, std::chars_format::general,
                                                   precision).ptr;
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

std::string exactNumber(double value) { return exactText(value); }

std::string exactVector(const glm::dvec3& v) {
    return exactText(v.x) + ',' + exactText(v.y) + ',' + exactText(v.z);
}

SceneFlags::SceneFlags(SceneOptions& options)
    : options_(options),
      eye_(vectorText(options.job.camera.eye)),
      target_(vectorText(options.job.camera.target)),
      up_(vectorText(options.job.camera.up)),
      size_(std::to_string(options.job.width) + "x" + std::to_string(options.job.height)),
      view_(debugViewName(options.job.shading.view)),
      background_(vectorText(glm::dvec3(options.job.background))) {}

void SceneFlags::addMapAndCamera(CLI::App& app) {
    SceneOptions& o = options_;
    app.add_option("--height", height_, "Height map image (any format OpenImageIO reads); default: the bundled map");
    app.add_option("--channel", o.load.channel, "Image channel holding the heights")->capture_default_str();
    app.add_flag("--normalize", o.load.normalize, "Map the map's [min, max] to [0, 1]");
    app.add_option("--height-scale", o.job.heightScale, "World height of map value 1 (the map spans 1 unit)")
        ->capture_default_str();
    app.add_option("--eye", eye_, "Camera position x,y,z (world, y up)")->capture_default_str();
    app.add_option("--target", target_, "Point the camera looks at, x,y,z")->capture_default_str();
    app.add_option("--up", up_, "Camera up direction x,y,z")->capture_default_str();
    app.add_option("--fovy", o.job.camera.fovyDegrees, "Vertical field of view in degrees")->capture_default_str();
    app.add_option("--size", size_, "Picture size WIDTHxHEIGHT")->capture_default_str();
}

void SceneFlags::addShading(CLI::App& app) {
    app.add_option("--light", light_, "Direction towards the light x,y,z (default -0.45,0.8,-0.35)");
    app.add_option("--view", view_,
                   "What the picture shows: shaded, or a debug view of the method: iterations (segments "
                   "visited, heat map), level (pyramid level where the ray stopped), normal, depth, position")
        ->capture_default_str();
    app.add_option("--background", background_, "Background colour r,g,b (linear, 0 to 1)")->capture_default_str();
}

void SceneFlags::apply() {
    SceneOptions& o = options_;
    if (!height_.empty()) o.heightFile = height_;
    o.job.camera.eye = parseVectorFlag("--eye", eye_);
    o.job.camera.target = parseVectorFlag("--target", target_);
    o.job.camera.up = parseVectorFlag("--up", up_);
    if (!light_.empty()) o.job.shading.lightDirection = glm::vec3(parseVectorFlag("--light", light_));
    if (glm::length(o.job.shading.lightDirection) == 0.0f) throwBadInput("--light must not be zero");
    parseSizeFlag(size_, o.job.width, o.job.height);
    o.job.shading.view = parseDebugView(view_);
    o.job.background = glm::vec3(parseVectorFlag("--background", background_));
    if (glm::any(glm::lessThan(o.job.background, glm::vec3(0.0f)))) throwBadInput("--background must be >= 0");
    if (!(o.job.heightScale > 0.0f) || !std::isfinite(o.job.heightScale)) {
        throwBadInput("--height-scale must be a positive number");
    }
    if (!(o.job.camera.fovyDegrees > 0.0 && o.job.camera.fovyDegrees < 180.0)) {
        throwBadInput("--fovy must lie strictly between 0 and 180 degrees");
    }
    if (o.load.channel < 0) throwBadInput("--channel must be >= 0");
}

std::string shellQuote(const std::string& text) {
    const bool plain = !text.empty() && text.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                               "0123456789_-+=.,/:@%") == std::string::npos;
    if (plain) return text;
    std::string quoted = "'";
    for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string renderCommandLine(const SceneOptions& o, const std::string& program) {
    const RenderJob& job = o.job;
    std::string line = program;
    const auto flag = [&](const std::string& name, const std::string& value) {
        line += " " + name + (value.empty() ? "" : " " + shellQuote(value));
    };
    if (o.heightFile) flag("--height", o.heightFile->string());
    if (o.load.channel != 0) flag("--channel", std::to_string(o.load.channel));
    if (o.load.normalize) flag("--normalize", "");
    flag("--height-scale", exactText(job.heightScale));
    // "=" keeps a leading minus from reading as a flag in any parser.
    line += " --eye=" + exactVector(job.camera.eye);
    line += " --target=" + exactVector(job.camera.target);
    line += " --up=" + exactVector(job.camera.up);
    flag("--fovy", exactText(job.camera.fovyDegrees));
    flag("--size", std::to_string(job.width) + "x" + std::to_string(job.height));
    line += " --light=" + exactVector(job.shading.lightDirection);
    flag("--view", debugViewName(job.shading.view));
    flag("--background", exactVector(job.background));
    return line;
}

}  // namespace microrelief
