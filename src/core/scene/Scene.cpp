#include "microrelief/core/scene/Scene.h"

#include <algorithm>
#include <cmath>

#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/scene/FloatLimits.h"

namespace microrelief {

namespace {

// A figure in a message (core/Text.h).
std::string number(double value) { return formatNumber(value, 9); }

std::string vectorText(const glm::dvec3& v) {
    return number(v.x) + "," + number(v.y) + "," + number(v.z);
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Runs a check of the library that throws, as a field's error.
template <class Check>
// The error's field is the first the message names, else `field`.
void collect(std::vector<FieldError>& errors, const std::string& field, Check check) {
    try {
        check();
    } catch (const Error& e) {
        std::string named;
        const std::string message = e.message([&](const std::string& f) {
            if (named.empty()) named = f;
            return "{" + f + "}";
        });
        errors.push_back({named.empty() ? field : named, message});
    }
}

}  // namespace

// A point: coordinates beyond the limit make exact hits impossible (core/scene/FloatLimits.h).
void checkPoint(std::vector<FieldError>& errors, const std::string& field, const glm::dvec3& p,
                double limit) {
    if (!finite(p) || std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > limit) {
        errors.push_back({field, "{" + field + "} " + vectorText(p) +
                                     ": each component must lie within +-" + number(limit) +
                                     (limit == kMaxWorldPosition
                                          ? " (world units; the renderer subtracts positions in "
                                            "double, which holds no more)"
                                          : " (world units, the relief spans 1; the shader's "
                                            "float arithmetic holds no more)")});
    }
}

// A direction the shader normalises in float: not zero, and not so short that its squared
// length underflows.
void checkDirection(std::vector<FieldError>& errors, const std::string& field, const glm::dvec3& v) {
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!finite(v)) {
        errors.push_back({field, "{" + field + "} must be finite"});
    } else if (largest == 0.0) {
        errors.push_back({field, "{" + field + "} must not be zero"});
    } else if (largest < kMinDirectionComponent) {
        errors.push_back({field, "{" + field + "} " + vectorText(v) +
                                     ": its largest component must be at least " +
                                     number(kMinDirectionComponent) +
                                     " (the shader normalises it in float)"});
    }
}

const std::vector<std::string>& animatedFieldNames() {
    static const std::vector<std::string> names = {"waves", "ripples", "flood"};
    return names;
}

bool ReliefDesc::operator==(const ReliefDesc& o) const {
    return map == o.map && albedo == o.albedo && base == o.base &&
           interpolation == o.interpolation && tiles == o.tiles && heightScale == o.heightScale &&
           model.objectToWorld() == o.model.objectToWorld() && animation == o.animation &&
           time == o.time && onMesh == o.onMesh && mesh == o.mesh;
}

namespace {

// What the mesh base (ReliefDesc::onMesh) does not draw yet: "{tiles} 2,1: not yet on the
// mesh base (--base mesh)".
std::string notYetOnMesh(const std::string& what) {
    return what + ": not yet on the mesh base ({base} mesh)";
}

// The relief's fields the mesh base takes or refuses: its file with it and only with it;
// tiles, an animation, a model transform and an albedo file not yet (gl/MeshRelief.h draws
// the mesh in its own units, one map over its uvs, in one colour).
void checkMesh(const ReliefDesc& relief, std::vector<FieldError>& errors) {
    if (!relief.onMesh) {
        if (relief.mesh.given())
            errors.push_back({"mesh.file", "{mesh.file} is the mesh base's: give {base} mesh with it "
                                           "(not {base} " +
                                               baseName(relief.base) + ")"});
        return;
    }
    if (!relief.mesh.given())
        errors.push_back({"mesh.file", "{base} mesh needs {mesh.file} FILE, the triangle mesh "
                                       "(OBJ or glTF 2.0) the map is laid over"});
    if (relief.tiles != glm::ivec2(1, 1))
        errors.push_back({"tiles", notYetOnMesh("{tiles} " + std::to_string(relief.tiles.x) + "," +
                                                std::to_string(relief.tiles.y) +
                                                " (the mesh's uvs repeat the map already)")});
    if (!relief.animation.empty())
        errors.push_back({"animation", notYetOnMesh("{animation} " + relief.animation)});
    if (!relief.model.isIdentity())
        errors.push_back({"model", notYetOnMesh("{model} (the mesh is drawn in its own units)")});
    if (relief.albedo.kind == AlbedoSource::Kind::File)
        errors.push_back({"albedo", notYetOnMesh("{albedo} FILE (colours from a file)")});
}

}  // namespace

std::vector<FieldError> ReliefDesc::validate() const {
    std::vector<FieldError> errors;
    if (map.load.channel < 0) errors.push_back({"map.load.channel", "{map.load.channel} must be >= 0"});
    if (map.samples && map.samples->samples.empty())
        errors.push_back({"map.samples", "{map.samples} holds no samples"});
    collect(errors, "base", [&] { validateBaseShape(base); });
    if (!(heightScale > 0.0f) || !std::isfinite(heightScale))
        errors.push_back({"heightScale", "{heightScale} must be a positive number"});
    if (tiles.x < 1 || tiles.y < 1 || tiles.x > kMaxTiles || tiles.y > kMaxTiles) {
        errors.push_back({"tiles", "{tiles} " + std::to_string(tiles.x) + "," + std::to_string(tiles.y) +
                                       ": each count must be a whole number from 1 to " +
                                       std::to_string(kMaxTiles)});
    }
    if (!animation.empty()) {
        const auto& names = animatedFieldNames();
        if (std::find(names.begin(), names.end(), animation) == names.end()) {
            std::string known;
            for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
            errors.push_back({"animation", "unknown {animation} '" + animation + "' (expected " + known + ")"});
        }
        if (tiles != glm::ivec2(1, 1))
            errors.push_back({"animation", "{animation} and {tiles}: an animated height field does not tile"});
    }
    if (!(std::abs(time) <= kMaxAnimationSeconds))
        errors.push_back({"time", "{time} must be a number of seconds within +-1e9, got " + number(time)});
    checkMesh(*this, errors);
    return errors;
}

bool ViewDesc::operator==(const ViewDesc& o) const {
    const auto methods = [](const MethodSettings& m) {
        return std::tuple(m.method, m.steps, m.minSteps, m.refineSteps, m.pixelError);
    };
    const auto shadings = [](const ShadingOptions& s) {
        return std::tuple(s.lightDirection, s.lightPosition, s.shadows, s.lightSizeDegrees, s.albedo,
                          s.albedoFinestLevel, s.view);
    };
    return camera.eye == o.camera.eye && camera.target == o.camera.target && camera.up == o.camera.up &&
           camera.fovyDegrees == o.camera.fovyDegrees && width == o.width && height == o.height &&
           methods(method) == methods(o.method) && shadings(shading) == shadings(o.shading) &&
           background == o.background;
}

std::optional<FieldError> pictureSizeError(int width, int height) {
    const double pixels = static_cast<double>(width) * height;
    if (width > 0 && height > 0 && width <= kMaxPictureSide && height <= kMaxPictureSide &&
        pixels <= static_cast<double>(kMaxPicturePixels))
        return std::nullopt;
    return FieldError{"size", "{size} " + std::to_string(width) + "x" + std::to_string(height) +
                                  " is outside the pictures this program renders: sides up to " +
                                  std::to_string(kMaxPictureSide) + ", at most " +
                                  std::to_string(kMaxPicturePixels) + " pixels (16384 x 16384; " +
                                  std::to_string(kFrameBytesPerPixel) + " bytes a pixel in memory)"};
}

void checkPictureSize(int width, int height) {
    if (std::optional<FieldError> size = pictureSizeError(width, height))
        throwBadInput(size->message);
}

std::vector<FieldError> ViewDesc::validate() const {
    std::vector<FieldError> errors;
    checkPoint(errors, "camera.eye", camera.eye);
    checkPoint(errors, "camera.target", camera.target);
    checkPoint(errors, "camera.up", camera.up, kMaxWorldCoordinate);
    checkDirection(errors, "camera.up", camera.up);
    if (errors.empty()) {
        // The camera resolves: a field of view, the eye apart from the target, an up that
        // is no view direction (core/scene/Camera.h says each, by field).
        collect(errors, "camera", [&] { resolveCamera(camera, 1, 1, 1.0); });
    }
    if (std::optional<FieldError> size = pictureSizeError(width, height))
        errors.push_back(std::move(*size));
    if (method.steps < 1 || method.steps > 65536)
        errors.push_back({"method.steps", "{method.steps} must lie in 1..65536"});
    if (!(method.pixelError >= 0.0f) || !std::isfinite(method.pixelError))
        errors.push_back({"method.pixelError", "{method.pixelError} must be a number >= 0"});
    if (shading.lightPosition) {
        checkPoint(errors, "shading.lightPosition", *shading.lightPosition);
    } else {
        checkDirection(errors, "shading.lightDirection", glm::dvec3(shading.lightDirection));
    }
    if (!(shading.lightSizeDegrees > 0.0f && shading.lightSizeDegrees < 90.0f))
        errors.push_back({"shading.lightSizeDegrees", "{shading.lightSizeDegrees} must lie strictly between 0 and 90 degrees"});
    if (!finite(glm::dvec3(background)) || glm::any(glm::lessThan(background, glm::vec3(0.0f))))
        errors.push_back({"background", "{background} must be >= 0"});
    return errors;
}

bool samePyramid(const ReliefDesc& a, const ReliefDesc& b) {
    return a.map == b.map && a.base.wrapsU() == b.base.wrapsU() && a.tiles == b.tiles;
}

std::vector<FieldError> validateTogether(const ReliefDesc& relief, const ViewDesc& view) {
    std::vector<FieldError> errors;
    if (relief.onMesh) {
        // What gl/MeshRelief.h draws: the multilevel method's exact hit, shaded under the
        // directional light or as normals; the rest is not there yet.
        if (view.method.method != Method::Multilevel)
            errors.push_back({"method", notYetOnMesh(std::string("{method} ") +
                                                     methodName(view.method.method) +
                                                     " (the mesh base is traced by multilevel)")});
        if (view.method.pixelError > 0.0f)
            errors.push_back({"method.pixelError",
                              notYetOnMesh("{method.pixelError} " + number(view.method.pixelError) +
                                           " (the mesh base is drawn exact, 0)")});
        if (view.shading.shadows != ShadowMode::Off)
            errors.push_back({"shading.shadows", notYetOnMesh(std::string("{shading.shadows} ") +
                                                              shadowModeName(view.shading.shadows))});
        if (view.shading.lightPosition)
            errors.push_back({"shading.lightPosition",
                              notYetOnMesh("{shading.lightPosition} (a point light; "
                                           "{shading.lightDirection} is drawn)")});
        if (view.shading.view != DebugView::Shaded && view.shading.view != DebugView::Normal)
            errors.push_back({"shading.view", notYetOnMesh(std::string("{shading.view} ") +
                                                           debugViewName(view.shading.view) +
                                                           " (shaded and normal are drawn)")});
        return errors;  // the analytic bases' rules below concern `base`, which is not drawn
    }
    collect(errors, "method", [&] { checkMethodSupportsBase(view.method.method, relief.base); });
    collect(errors, "method", [&] { checkMethodSupportsTiles(view.method.method, relief.tiles); });
    if (view.shading.shadows != ShadowMode::Off && !methodTracesTheSolid(view.method.method)) {
        errors.push_back({"shading.shadows", std::string("{shading.shadows} ") +
                                                 shadowModeName(view.shading.shadows) +
                                                 " takes the exact methods, " +
                                                 methodNamesWith(MethodTrait::Solid) + " (not {method} " +
                                                 methodName(view.method.method) + ")"});
    }
    return errors;
}

std::vector<FieldError> validateScene(const ReliefDesc& relief, const ViewDesc& view) {
    std::vector<FieldError> errors = relief.validate();
    for (auto& e : view.validate()) errors.push_back(std::move(e));
    for (auto& e : validateTogether(relief, view)) errors.push_back(std::move(e));
    return errors;
}

void throwIfInvalid(const std::vector<FieldError>& errors) {
    if (!errors.empty()) throwBadInput(errors.front().message);
}

}  // namespace microrelief
