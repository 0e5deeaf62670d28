#include "microrelief/core/scene/Method.h"

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {
constexpr const char* kDebugViewNames[] = {"shaded", "iterations", "level",
                                           "normal", "depth",      "position"};
constexpr const char* kShadowModeNames[] = {"off", "hard", "soft"};
constexpr const char* kMethodNames[] = {"multilevel", "normal", "offset", "steep", "pom",
                                        "relief",     "maxmip", "cone",   "rcsm"};

// The enum value whose name is `name`, by position in `names`; throws Error(BadInput)
// naming the flag and the choices.
template <class Enum, std::size_t N>
Enum parseName(const char* const (&names)[N], const std::string& name, const char* flag) {
    std::string choices;
    for (std::size_t k = 0; k < N; ++k) {
        if (name == names[k]) return static_cast<Enum>(k);
        choices += std::string(k == 0 ? "" : k + 1 == N ? " or " : ", ") + names[k];
    }
    throwBadInput(std::string("unknown ") + flag + " '" + name + "' (expected " + choices + ")");
}
}  // namespace

Method parseMethod(const std::string& name) {
    return parseName<Method>(kMethodNames, name, "{method}");
}

const char* methodName(Method method) {
    return kMethodNames[static_cast<int>(method)];
}

bool methodHasSteps(Method method) {
    return method == Method::Steep || method == Method::Pom || method == Method::Relief ||
           method == Method::Rcsm;
}

bool methodTracesTheSolid(Method method) {
    return method == Method::Multilevel || method == Method::MaxMip || method == Method::Cone;
}

bool methodRunsOnBase(Method method, const BaseShape& base) {
    return !base.curved() || method == Method::Multilevel || method == Method::MaxMip ||
           method == Method::Pom || method == Method::Relief;
}

void checkMethodSupportsBase(Method method, const BaseShape& base) {
    if (methodRunsOnBase(method, base)) return;
    throwBadInput(std::string("{method} ") + methodName(method) + " does not run on {base} " +
                  baseName(base) + " (curved bases take multilevel, maxmip, pom and relief)");
}

ShadowMode parseShadowMode(const std::string& name) {
    return parseName<ShadowMode>(kShadowModeNames, name, "{shading.shadows}");
}

const char* shadowModeName(ShadowMode mode) {
    return kShadowModeNames[static_cast<int>(mode)];
}

bool methodTakesTiles(Method method) {
    return method != Method::MaxMip && method != Method::Cone && method != Method::Rcsm;
}

void checkMethodSupportsTiles(Method method, glm::ivec2 tiles) {
    if (tiles == glm::ivec2(1, 1) || methodTakesTiles(method)) return;
    if (method == Method::MaxMip) {
        throwBadInput(
            "{method} maxmip does not take {tiles} (its quadtree is the map's own; the "
            "multilevel method and the step-based peers do)");
    }
    if (method == Method::Cone || method == Method::Rcsm) {
        throwBadInput(std::string("{method} ") + methodName(method) +
                      " does not take {tiles} (its cone map is the map's own; the multilevel "
                      "method and the step-based peers do)");
    }
}

DebugView parseDebugView(const std::string& name) {
    return parseName<DebugView>(kDebugViewNames, name, "{shading.view}");
}

const char* debugViewName(DebugView view) {
    return kDebugViewNames[static_cast<int>(view)];
}

}  // namespace microrelief
