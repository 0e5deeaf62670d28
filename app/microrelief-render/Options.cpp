#include "Options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/Error.h"

namespace microrelief {

namespace {

// "x,y,z" -> vector; the spec's form for --eye, --target, --up, --light.
glm::dvec3 parseVector(const std::string& flag, const std::string& text) {
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

void parseSize(const std::string& text, int& width, int& height) {
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

std::string vectorText(const glm::dvec3& v) {
    std::ostringstream out;
    out << v.x << ',' << v.y << ',' << v.z;
    return out.str();
}

}  // namespace

ParseResult parseRenderOptions(int argc, char** argv) {
    RenderOptions o;
    CLI::App app{
        "Renders a height map as microrelief, ray traced per pixel by multilevel binary subdivision\n"
        "(Vyatkin & Romaniuk), headless through EGL or OSMesa.",
        "microrelief-render"};
    app.get_formatter()->column_width(34);

    std::string height, eye = vectorText(o.job.camera.eye), target = vectorText(o.job.camera.target),
                       up = vectorText(o.job.camera.up), size = "1280x720", backend = "auto", aov, light;
    std::string out = o.out.string();
    app.add_option("--height", height, "Height map image (any format OpenImageIO reads); default: the bundled map");
    app.add_option("--channel", o.load.channel, "Image channel holding the heights")->capture_default_str();
    app.add_flag("--normalize", o.load.normalize, "Map the map's [min, max] to [0, 1]");
    app.add_option("--height-scale", o.job.heightScale, "World height of map value 1 (the map spans 1 unit)")
        ->capture_default_str();
    app.add_option("--eye", eye, "Camera position x,y,z (world, y up)")->capture_default_str();
    app.add_option("--target", target, "Point the camera looks at, x,y,z")->capture_default_str();
    app.add_option("--up", up, "Camera up direction x,y,z")->capture_default_str();
    app.add_option("--fovy", o.job.camera.fovyDegrees, "Vertical field of view in degrees")->capture_default_str();
    app.add_option("--size", size, "Picture size WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--out", out, "Shaded picture; the format follows the extension")->capture_default_str();
    app.add_option("--aov", aov, "World position AOV, OpenEXR: R,G,B = hit x,y,z, A = 1 hit / 0 miss");
    app.add_option("--light", light, "Direction towards the light x,y,z (default -0.45,0.8,-0.35)");
    std::string method = "multilevel";
    app.add_option("--method", method,
                   "How rays are traced: multilevel (the paper's method, exact), or a peer for comparison: "
                   "normal, offset, steep, pom, relief, maxmip")
        ->capture_default_str();
    app.add_option("--steps", o.job.method.steps,
                   "Peers' quality knob: steep layers, pom samples at grazing angles, relief linear steps")
        ->capture_default_str();
    app.add_option("--pixel-error", o.job.method.pixelError,
                   "multilevel: stop at pyramid levels whose texels project to less than this many pixels "
                   "(0: exact)")
        ->capture_default_str();
    std::string view = "shaded";
    app.add_option("--view", view,
                   "What the picture shows: shaded, or a debug view of the method: iterations (segments "
                   "visited, heat map), level (pyramid level where the ray stopped), normal, depth, position")
        ->capture_default_str();
    app.add_option("--backend", backend, "GL backend: auto (EGL, then OSMesa), egl or osmesa")
        ->capture_default_str();
    app.add_flag("--compare-reference", o.compareReference,
                 "Also trace every pixel with the exact CPU reference and print how the picture differs");
    app.add_flag("-q,--quiet", o.quiet, "Print nothing on success");
    app.add_flag("-v,--verbose", o.verbose, "Print the GL renderer and shader logs");
    app.set_version_flag("--version", std::string("microrelief-render ") + MICRORELIEF_VERSION);
    app.allow_windows_style_options(false);

    ParseResult result;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        result.message = app.help();
        return result;
    } catch (const CLI::CallForVersion& e) {
        result.message = e.what();
        return result;
    } catch (const CLI::ParseError& e) {
        result.exitStatus = 2;
        result.message = std::string(e.what()) + " (see --help)";
        return result;
    }

    try {
        if (!height.empty()) o.heightFile = height;
        o.job.camera.eye = parseVector("--eye", eye);
        o.job.camera.target = parseVector("--target", target);
        o.job.camera.up = parseVector("--up", up);
        if (!light.empty()) o.job.shading.lightDirection = glm::vec3(parseVector("--light", light));
        if (glm::length(o.job.shading.lightDirection) == 0.0f) throwBadInput("--light must not be zero");
        parseSize(size, o.job.width, o.job.height);
        o.backend = parseBackend(backend);
        o.job.shading.view = parseDebugView(view);
        o.job.method.method = parseMethod(method);
        if (o.job.method.steps < 1 || o.job.method.steps > 65536) throwBadInput("--steps must lie in 1..65536");
        o.job.method.minSteps = std::max(1, std::min(o.job.method.minSteps, o.job.method.steps));
        if (!(o.job.method.pixelError >= 0.0f) || !std::isfinite(o.job.method.pixelError)) {
            throwBadInput("--pixel-error must be a number >= 0");
        }
        o.out = out;
        if (!aov.empty()) o.aov = aov;
        if (!(o.job.heightScale > 0.0f) || !std::isfinite(o.job.heightScale)) {
            throwBadInput("--height-scale must be a positive number");
        }
        if (!(o.job.camera.fovyDegrees > 0.0 && o.job.camera.fovyDegrees < 180.0)) {
            throwBadInput("--fovy must lie strictly between 0 and 180 degrees");
        }
        if (o.load.channel < 0) throwBadInput("--channel must be >= 0");
    } catch (const Error& e) {
        result.exitStatus = 2;
        result.message = e.what();
        return result;
    }
    result.options = std::move(o);
    return result;
}

}  // namespace microrelief
