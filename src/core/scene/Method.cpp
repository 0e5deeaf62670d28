#include "microrelief/core/scene/Method.h"

#include <iterator>
#include <string_view>
#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/Text.h"

namespace microrelief {

namespace {
constexpr const char* kDebugViewNames[] = {"shaded", "iterations", "level",
                                           "normal", "depth",      "position"};
constexpr const char* kShadowModeNames[] = {"off", "hard", "soft"};

// The methods' names and rows are variants.glsl's (generated: core/GlslConstants.h), in
// the order of the enum, which src/gl/ReliefShader.cpp holds to them value by value.
static_assert(glsl::kMethodCount == static_cast<int>(Method::Rcsm) + 1);
constexpr bool bitIs(MethodTrait trait, unsigned bit) {
    return static_cast<unsigned>(trait) == bit;
}
static_assert(bitIs(MethodTrait::Steps, glsl::kMethodTraitSteps) &&
                  bitIs(MethodTrait::Solid, glsl::kMethodTraitSolid) &&
                  bitIs(MethodTrait::Curved, glsl::kMethodTraitCurved) &&
                  bitIs(MethodTrait::TangentFrame, glsl::kMethodTraitTangentFrame) &&
                  bitIs(MethodTrait::Tiles, glsl::kMethodTraitTiles) &&
                  bitIs(MethodTrait::OffRay, glsl::kMethodTraitOffRay) &&
                  bitIs(MethodTrait::MaxPyramid, glsl::kMethodTraitMaxPyramid) &&
                  bitIs(MethodTrait::ConeMap, glsl::kMethodTraitConeMap) &&
                  bitIs(MethodTrait::RelaxedConeMap, glsl::kMethodTraitRelaxedConeMap),
              "MethodTrait's bits are the GLSL's trait bits (core/GlslConstants.h)");

}  // namespace

std::string methodNamesWith(MethodTrait trait) {
    std::vector<std::string> names;
    for (int m = 0; m < glsl::kMethodCount; ++m) {
        if (methodHas(static_cast<Method>(m), trait)) names.push_back(glsl::kMethodValues[m].name);
    }
    return joinWords(names, " and ");
}

namespace {

// The enum value whose name is `name`, by position in `names`; throws Error(BadInput)
// naming the flag and the choices.
template <class Enum, std::size_t N>
Enum parseName(const char* const (&names)[N], const std::string& name, const char* flag) {
    for (std::size_t k = 0; k < N; ++k) {
        if (name == names[k]) return static_cast<Enum>(k);
    }
    throwBadInput(std::string("unknown ") + flag + " '" + name + "' (expected " +
                  joinWords({std::begin(names), std::end(names)}, " or ") + ")");
}
}  // namespace

bool methodHas(Method method, MethodTrait trait) {
    return (glsl::kMethodTraits[static_cast<int>(method)] & static_cast<unsigned>(trait)) != 0;
}

Method parseMethod(const std::string& name) {
    std::vector<std::string> choices;
    for (int m = 0; m < glsl::kMethodCount; ++m) {
        if (name == glsl::kMethodValues[m].name) return static_cast<Method>(m);
        choices.push_back(glsl::kMethodValues[m].name);
    }
    throwBadInput("unknown {method} '" + name + "' (expected " + joinWords(choices, " or ") + ")");
}

const char* methodName(Method method) {
    return glsl::kMethodValues[static_cast<int>(method)].name;
}

bool methodRunsOnBase(Method method, const BaseShape& base) {
    return !base.curved() || methodHas(method, MethodTrait::Curved);
}

void checkMethodSupportsBase(Method method, const BaseShape& base) {
    if (methodRunsOnBase(method, base)) return;
    throwBadInput(std::string("{method} ") + methodName(method) + " does not run on {base} " +
                  baseName(base) + " (curved bases take " + methodNamesWith(MethodTrait::Curved) +
                  ")");
}

ShadowMode parseShadowMode(const std::string& name) {
    return parseName<ShadowMode>(kShadowModeNames, name, "{shading.shadows}");
}

const char* shadowModeName(ShadowMode mode) {
    return kShadowModeNames[static_cast<int>(mode)];
}

void checkMethodSupportsTiles(Method method, glm::ivec2 tiles) {
    if (tiles == glm::ivec2(1, 1) || methodTakesTiles(method)) return;
    // What it reads that is the map's own, untiled.
    const char* own = methodHas(method, MethodTrait::MaxPyramid) ? "quadtree" : "cone map";
    throwBadInput(std::string("{method} ") + methodName(method) + " does not take {tiles} (its " +
                  own + " is the map's own; " + methodNamesWith(MethodTrait::Tiles) + " do)");
}

DebugView parseDebugView(const std::string& name) {
    return parseName<DebugView>(kDebugViewNames, name, "{shading.view}");
}

const char* debugViewName(DebugView view) {
    return kDebugViewNames[static_cast<int>(view)];
}

}  // namespace microrelief
