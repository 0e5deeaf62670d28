// What a picture is traced and shaded with: the method (the paper's multilevel method or
// one of the peers it is measured against) and its settings, the debug views, the light
// and material. Plain values, parsed from and named by the programs' flags; relief.frag's
// macros and uniforms take them (gl/ReliefShader.h).
#pragma once

#include <algorithm>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"

namespace microrelief {

// How each pixel's ray is traced (relief.frag's MICRORELIEF_METHOD): the paper's
// multilevel method, or one of the peers it is measured against (cone: cone step mapping
// with conservative cones and an exact last texel; rcsm: relaxed cone stepping as
// published; both over a cone map, peers/ConeMap.h).
enum class Method { Multilevel = 0, Normal, Offset, Steep, Pom, Relief, MaxMip, Cone, Rcsm };

// What a method is: the traits of its row, written once in
// shaders/microrelief/variants.glsl (MR_TRAITS_MAXMIP ...), where relief.frag and the pages
// read them too; each value here is its MR_TRAIT_* bit (Method.cpp asserts them).
enum class MethodTrait : unsigned {
    Steps = 1,              // its quality knob is a step count (--steps)
    Solid = 2,              // traces the whole solid, side walls and bottom face included:
                            // exact, and its hits take self-shadows
    Curved = 4,             // runs on the curved bases
    TangentFrame = 8,       // on a curved base, steps in the base's tangent frame where the
                            // ray enters the shell, as engines run it there
    Tiles = 16,             // takes a tiled map (--tile)
    OffRay = 32,            // its answer is a map point off the ray (a shifted lookup)
    MaxPyramid = 64,        // reads the map's own quadtree (aligned max levels)
    ConeMap = 128,          // reads a conservative cone map (peers/ConeMap.h)
    RelaxedConeMap = 256,   // reads a relaxed cone map
};

// Whether `method`'s row has `trait`.
bool methodHas(Method method, MethodTrait trait);
// The methods whose rows have `trait`, for messages: "multilevel, maxmip and cone".
std::string methodNamesWith(MethodTrait trait);

// "multilevel", "normal", "offset", "steep", "pom", "relief", "maxmip", "cone", "rcsm" (the
// values of the GLSL's methods, core/GlslConstants.h); throws Error(BadInput).
Method parseMethod(const std::string& name);
const char* methodName(Method method);
// Whether a method's quality knob is a step count (steep, pom, relief, rcsm).
inline bool methodHasSteps(Method method) {
    return methodHas(method, MethodTrait::Steps);
}
// Whether a method traces the whole solid, side walls and bottom face included
// (multilevel, maxmip, cone); the others know the top surface only.
inline bool methodTracesTheSolid(Method method) {
    return methodHas(method, MethodTrait::Solid);
}
// Whether a method runs on a base: every method on the plane; on a curved base the exact
// ones (multilevel, maxmip) and the peers engines ship there, pom and relief stepping in
// the base's tangent frame. Otherwise throws Error(BadInput) naming both flags and the
// methods that do.
void checkMethodSupportsBase(Method method, const BaseShape& base);
// Whether a method takes a tiled map (--tile): every method but maxmip, whose quadtree is
// the map's own, and cone and rcsm, whose cone maps are. Otherwise throws Error(BadInput)
// naming both flags.
void checkMethodSupportsTiles(Method method, glm::ivec2 tiles);
bool methodRunsOnBase(Method method, const BaseShape& base);
inline bool methodTakesTiles(Method method) {
    return methodHas(method, MethodTrait::Tiles);
}

struct MethodSettings {
    Method method = Method::Multilevel;
    int steps = 64;           // steep: layers; pom: samples at grazing angles; relief: linear
                              // steps; rcsm: relaxed cone steps (15 as published)
    int minSteps = 16;        // pom: samples looking straight down (setSteps: a quarter, >= 4)
    int refineSteps = 8;      // relief, rcsm: binary search steps
    float pixelError = 0.0f;  // multilevel: tolerated error in pixels; 0 is exact

    // The step budget and what follows from it, the one rule every program uses.
    void setSteps(int n) {
        steps = n;
        minSteps = std::min(n, std::max(4, n / 4));
    }
};

// What relief.frag writes to the picture (debug_views.glsl).
enum class DebugView { Shaded = 0, Iterations, Level, Normal, Depth, Position };

// "shaded", "iterations", "level", "normal", "depth", "position"; throws Error(BadInput).
DebugView parseDebugView(const std::string& name);
const char* debugViewName(DebugView view);

// Self-shadows (shadow.glsl): none; hard, exact (a second trace from each hit towards the
// light); or soft, an estimate for a round light of some angular size.
enum class ShadowMode { Off = 0, Hard = 1, Soft = 2 };

// "off", "hard", "soft"; throws Error(BadInput) naming --shadows.
ShadowMode parseShadowMode(const std::string& name);
const char* shadowModeName(ShadowMode mode);

struct ShadingOptions {
    glm::vec3 lightDirection =
        glm::normalize(glm::vec3(-0.45f, 0.8f, -0.35f));  // towards a directional light
    // A point light at this world position instead (--light-position).
    std::optional<glm::dvec3> lightPosition;  // double: the renderer subtracts the eye first
    ShadowMode shadows = ShadowMode::Off;
    float lightSizeDegrees = 1.0f;          // soft shadows: the light's angular diameter
    glm::vec3 albedo{0.60f, 0.58f, 0.55f};  // without an albedo texture
    // With one: filtered over each pixel's footprint, or its finest level only (what a
    // supersampled reference takes, per ray).
    bool albedoFinestLevel = false;
    DebugView view = DebugView::Shaded;
};

}  // namespace microrelief
