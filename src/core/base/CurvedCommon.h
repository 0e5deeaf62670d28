// Internal to src/core/base: what the curved bases' files share.
#pragma once

#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

namespace microrelief::curved {

inline constexpr double kPi = std::numbers::pi;

// The parameter interval where |p(t)| <= radius for p = o + t d in `dims` dimensions (the
// xz plane for the cylinder, space for the ellipsoid), from the point nearest the centre,
// which keeps far origins accurate. Empty (x > y) when the line passes outside.
template <int N>
inline glm::dvec2 insideRadius(const glm::vec<N, double>& o, const glm::vec<N, double>& d,
                               double radius) {
    const double dd = glm::dot(d, d);
    if (dd == 0.0)
        return glm::dot(o, o) <= radius * radius ? glm::dvec2(-HUGE_VAL, HUGE_VAL)
                                                 : glm::dvec2(1.0, -1.0);
    const double tc = -glm::dot(o, d) / dd;
    const glm::vec<N, double> pc = o + tc * d;
    const double h2 = (radius * radius - glm::dot(pc, pc)) / dd;
    if (h2 < 0.0) return {1.0, -1.0};
    const double half = std::sqrt(h2);
    return {tc - half, tc + half};
}

}  // namespace microrelief::curved
