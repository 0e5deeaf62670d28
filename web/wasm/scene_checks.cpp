// scene_checks.cpp: the programs' checks of a scene, for the browser front ends (the web
// page and examples/three, docs/browser.md "One validation"): the library's own C++
// (core/scene/Scene.h: validateScene; Camera.h: resolveCamera; FloatLimits.h:
// checkFloatLimits; the table of bases; ModelTransform's checks), unchanged, behind a C
// interface, compiled to WebAssembly by web/wasm/CMakeLists.txt (the page's
// web/generated/scene_checks_wasm.js) and by packages/microrelief-three/scripts/build.mjs
// (the package's generated/scene_checks_wasm.js). web/scene_checks.js drives it.
//
// A scene is set field by field (mr_scene_reset, then the setters), in the order
// microrelief-render's SceneFlags::apply turns its flags into a scene; the first error a
// setter meets is kept (as the program stops at its first), and mr_scene_check reports it
// or, with none, the first of validateScene and then checkFloatLimits'. Messages name the
// scene's fields as the caller's names for them (mr_set_field_name: the page's URL keys),
// as a program names them as its flags.
#include <cstring>
#include <exception>
#include <map>
#include <optional>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/FloatLimits.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/core/scene/SceneFields.h"

using namespace microrelief;

namespace {

struct State {
    ReliefDesc relief;
    ViewDesc view;
    std::optional<Error> error;  // the first a setter met
};

State state;
std::map<std::string, std::string> fieldNames;  // field -> the caller's name for it
std::string lastError, fieldList;

// Runs a setter's work; its Error, if it is the first, is kept for mr_scene_check.
template <class Work>
void apply(Work work) {
    if (state.error) return;
    try {
        work();
    } catch (const Error& e) {
        state.error = e;
    }
}

std::string named(const Error& e) {
    return e.message([](const std::string& field) {
        const auto found = fieldNames.find(field);
        return found == fieldNames.end() ? field : found->second;
    });
}

}  // namespace

extern "C" {

// The caller's name for a scene field in messages ("camera.fovyDegrees" -> "fovy").
void mr_set_field_name(const char* field, const char* name) {
    fieldNames[field] = name;
}

// Every field a message may name, one a line: the scene's and the bases' sizes.
const char* mr_scene_fields() {
    fieldList.clear();
    for (const std::string& field : sceneFields()) fieldList += field + "\n";
    for (const std::string& field : baseSizeFields()) fieldList += field + "\n";
    return fieldList.c_str();
}

// The scene the programs start from: every field at its default, no error.
void mr_scene_reset() {
    state = State{};
}

// --base NAME: the row of the table of bases, at its default sizes.
void mr_scene_set_base(const char* name) {
    apply([&] { state.relief.base = baseType(name).defaults; });
}

// One of the base's sizes ("base.radius", 1 number; "base.radii", 3), as --radius sets it.
void mr_scene_set_base_size(const char* field, double x, double y, double z) {
    apply([&] {
        const BaseType& type = baseType(state.relief.base);
        for (const BaseSize& size : type.sizes) {
            if (field != std::string(size.field)) continue;
            const double numbers[3] = {x, y, z};
            for (int i = 0; i < size.count; ++i)
                if (!(numbers[i] > 0.0))
                    throwBadInput(std::string("{") + field + "} must be a positive finite number");
            size.write(state.relief.base, numbers);
            return;
        }
        throwBadInput(std::string("{") + field + "} does not apply to {base} " + type.name);
    });
}

void mr_scene_set_relief(float heightScale, const char* interpolation) {
    state.relief.heightScale = heightScale;
    apply([&] { state.relief.interpolation = parseInterpolation(interpolation); });
}

// --model: 12 numbers, a 3 x 4 matrix in rows.
void mr_scene_set_model(const double* rows) {
    apply([&] {
        std::array<double, 12> m{};
        std::memcpy(m.data(), rows, sizeof(m));
        state.relief.model = ModelTransform::fromRows(m);
    });
}

void mr_scene_set_camera(double eyeX, double eyeY, double eyeZ, double targetX, double targetY,
                         double targetZ, double upX, double upY, double upZ, double fovyDegrees) {
    state.view.camera =
        Camera{{eyeX, eyeY, eyeZ}, {targetX, targetY, targetZ}, {upX, upY, upZ}, fovyDegrees};
}

// The picture, pixels (--size).
void mr_scene_set_size(int width, int height) {
    state.view.width = width;
    state.view.height = height;
}

void mr_scene_set_method(const char* method, int steps, float pixelError) {
    apply([&] { state.view.method.method = parseMethod(method); });
    state.view.method.steps = steps;
    if (steps >= 1 && steps <= 65536) state.view.method.setSteps(steps);
    state.view.method.pixelError = pixelError;
}

// The light towards which surfaces are lit (--light): checked in double, before it is
// stored in float, as the programs check it.
void mr_scene_set_light(double x, double y, double z) {
    apply([&] {
        std::vector<FieldError> errors;
        checkDirection(errors, "shading.lightDirection", {x, y, z});
        throwIfInvalid(errors);
        state.view.shading.lightDirection = glm::vec3(x, y, z);
    });
}

void mr_scene_set_shading(const char* shadows, float lightSizeDegrees, const char* view) {
    apply([&] { state.view.shading.shadows = parseShadowMode(shadows); });
    state.view.shading.lightSizeDegrees = lightSizeDegrees;
    apply([&] { state.view.shading.view = parseDebugView(view); });
}

void mr_scene_set_background(float r, float g, float b) {
    state.view.background = {r, g, b};
}

// 1 when the scene set is one the programs draw; else 0, and mr_last_error() says why.
// With a map (`mapWidth` > 0: its size, the tiled whole, and its largest sample) the float
// limits are checked too, for the picture set (mr_scene_set_size), naming the map `source`.
int mr_scene_check(int mapWidth, int mapHeight, double maxHeight, const char* source) {
    try {
        if (state.error) throw *state.error;
        throwIfInvalid(validateScene(state.relief, state.view));
        if (mapWidth > 0) {
            const Camera& camera = state.view.camera;
            checkFloatLimits({mapWidth, mapHeight, maxHeight}, state.relief.heightScale,
                             state.relief.base, state.relief.model, camera,
                             resolveCamera(camera, state.view.width, state.view.height, 1.0),
                             source);
        }
    } catch (const Error& e) {
        lastError = named(e);
        return 0;
    } catch (const std::exception& e) {
        lastError = std::string("the scene checks failed: ") + e.what();
        return 0;
    }
    return 1;
}

const char* mr_last_error() {
    return lastError.c_str();
}
}
