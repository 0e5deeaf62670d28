// Internal to src/core/base: what the curved bases' files share.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

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

// The least and the most length of a curved base's object-space normals (the float limits'
// check 3), from the most length `frameMax` of a frame normal: at least 1 in the frame (its
// radial part r >= 1; the caps' normals are unit), then through the frame's inverse
// transpose, object = frame / scale.
inline std::pair<double, double> objectNormalRange(const glm::dvec3& scale, double frameMax) {
    const double least = std::min({scale.x, scale.y, scale.z});
    const double most = std::max({scale.x, scale.y, scale.z});
    return {1.0 / most, frameMax / least};
}

// The angle about the axis of map column X (texels) on a map W wide: u = X / W, the seam
// u = 0 at -z (BaseShape.h).
inline double angleOf(double x, int width) {
    return 2.0 * kPi * (x / width - 0.5);
}

}  // namespace microrelief::curved
