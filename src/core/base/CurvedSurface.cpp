// What the cylinder and the ellipsoid share: the canonical frame (world = scale * q), the
// angle about the y axis that sets u, and the footprint built from it.
// shaders/microrelief/base_curved.glsl is the shader's copy.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/GlslConstants.h"

namespace microrelief {

FrameRay CurvedSurface::frameRay(const Ray& world) const {
    return {world.origin / frameScale_, world.direction / frameScale_};
}

glm::dvec3 CurvedSurface::worldNormal(const glm::dvec3& n) const {
    return glm::normalize(n / frameScale_);  // the inverse transpose of diag(scale)
}

double CurvedSurface::mapX(const glm::dvec3& q) const {
    // u = fract(0.5 + atan2(q.x, q.z) / 2 pi): 0.5 faces +z, the seam u = 0 is at -z.
    const double u = 0.5 + std::atan2(q.x, q.z) / (2.0 * std::numbers::pi);
    return width_ * (u - std::floor(u));
}

// base_curved.glsl: MR_CURVED_FINAL_LENGTH, the curvature's bound on a final piece.
double CurvedSurface::finalLength() const { return glsl::kCurvedFinalLength; }

bool CurvedSurface::xIncreases(const FrameRay& ray) const {
    // d(atan2(x, z))/dt = (z dx - x dz) / (x^2 + z^2): its sign is constant along a line.
    return ray.origin.z * ray.dir.x - ray.origin.x * ray.dir.z > 0.0;
}

std::optional<double> CurvedSurface::crossX(const FrameRay& ray, double boundary,
                                            double after) const {
    // The half-plane through the axis at angle phi: points lambda (sin phi, y, cos phi),
    // lambda >= 0. The line meets its plane where sin(phi) z - cos(phi) x = 0.
    const double phi = 2.0 * std::numbers::pi * (boundary / width_ - 0.5);
    const double s = std::sin(phi), c = std::cos(phi);
    const double denominator = s * ray.dir.z - c * ray.dir.x;
    if (denominator == 0.0) return std::nullopt;  // parallel to that plane
    const double t = (c * ray.origin.x - s * ray.origin.z) / denominator;
    const glm::dvec3 p = ray.at(t);
    if (s * p.x + c * p.z <= 0.0) return std::nullopt;  // the opposite half-plane
    // Behind `after` and nearer the axis than the path there: a line through the axis meets
    // the plane on it, no crossing (base_curved.glsl: mr_curvedCrossX).
    if (t < after) {
        const glm::dvec3 q = ray.at(after);
        if (p.x * p.x + p.z * p.z < 0.25 * (q.x * q.x + q.z * q.z)) return std::nullopt;
    }
    return t;
}

Footprint CurvedSurface::footprint(const FrameRay& ray, double ta, double tb) const {
    Footprint f;
    const glm::dvec3 pa = ray.at(ta), pb = ray.at(tb);
    // X: the angle about the axis is monotone along a line and a segment that does not
    // meet the axis turns by less than half a turn, so its path covers exactly the
    // shorter arc between its ends. Near half a turn the segment passes next to the axis
    // (where rounding could pick the wrong arc, and a segment through it jumps by half a
    // turn): all of u then.
    const double w = width_, xa = mapX(pa), xb = mapX(pb);
    double arc = xb - xa;
    if (arc > 0.5 * w) arc -= w;
    if (arc < -0.5 * w) arc += w;
    if (std::abs(arc) >= 0.5 * w - 2.0 * kFootprintMargin) {
        f.lo.x = 0.0;
        f.hi.x = w;
    } else {
        f.lo.x = std::min(xa, xa + arc) - kFootprintMargin;
        f.hi.x = std::max(xa, xa + arc) + kFootprintMargin;
        if (f.lo.x < 0.0) {
            f.lo.x += w;
            f.hi.x += w;
        }
    }
    const glm::dvec2 y = rangeY(ray, ta, tb);
    f.lo.y = y.x - kFootprintMargin;
    f.hi.y = y.y + kFootprintMargin;
    f.lowest = lowest(ray, ta, tb);
    f.drop = std::abs(radial(pb) - radial(pa)) / heightScale_;
    return f;
}

double CurvedSurface::lowest(const FrameRay& ray, double ta, double tb) const {
    return (lowestRadial(ray, ta, tb) - kRadiusMargin - 1.0) / heightScale_;
}

double CurvedSurface::descendTo(const FrameRay& ray, double ta, double tb, double h) const {
    // Where the ray enters the shell of that height's radius, widened by the margin so
    // that it is never late.
    const glm::dvec2 inside = insideRadial(ray, 1.0 + heightScale_ * h + kRadiusMargin);
    return inside.x > ta && inside.x <= tb ? inside.x : ta;
}

}  // namespace microrelief
