// The ellipsoid base (BaseShape.h): the unit sphere in the frame; v is the latitude from the +y
// pole. shaders/microrelief/base_ellipsoid.glsl is the shader's copy.
#include <algorithm>
#include <cmath>

#include "core/base/CurvedCommon.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"

namespace microrelief {

namespace {

using curved::insideRadius;
using curved::kPi;

// The ellipsoid: the unit sphere in the frame; v is the latitude from the +y pole.
class EllipsoidSurface final : public CurvedSurface {
public:
    using CurvedSurface::CurvedSurface;

    glm::dvec2 insideRadial(const FrameRay& ray, double r) const override {
        return insideRadius<3>(ray.origin, ray.dir, r);
    }
    double radial(const glm::dvec3& q) const override { return glm::length(q); }
    // The polar angle as atan2(|q.xz|, q.y): well conditioned at the poles, where
    // acos(q.y / r) loses half the digits (base_ellipsoid.glsl does the same).
    double mapY(const glm::dvec3& q) const override {
        return height_ * std::atan2(std::hypot(q.x, q.z), q.y) / kPi;
    }

    double lowestRadial(const FrameRay& ray, double ta, double tb) const override {
        const double dd = glm::dot(ray.dir, ray.dir);
        const double t = std::clamp(-glm::dot(ray.origin, ray.dir) / dd, ta, tb);
        return glm::length(ray.at(t));
    }

    // q.y / |q| along o + t d has the derivative N(t) / |p|^3 with N linear in t:
    // N(t) = dy |o|^2 - oy (o.d) + t (dy (o.d) - oy |d|^2). Its one root is the
    // latitude's only interior extremum.
    std::optional<double> turnY(const FrameRay& ray) const override {
        const glm::dvec3 o = ray.origin, d = ray.dir;
        const double od = glm::dot(o, d);
        const double slope = d.y * od - o.y * glm::dot(d, d);
        if (slope == 0.0) return std::nullopt;
        return -(d.y * glm::dot(o, o) - o.y * od) / slope;
    }

    glm::dvec2 rangeY(const FrameRay& ray, double ta, double tb) const override {
        double ya = mapY(ray.at(ta)), yb = mapY(ray.at(tb));
        glm::dvec2 range(std::min(ya, yb), std::max(ya, yb));
        if (const auto t = turnY(ray); t && *t > ta && *t < tb) {
            const double y = mapY(ray.at(*t));
            range = {std::min(range.x, y), std::max(range.y, y)};
        }
        return range;
    }

    // The cone of latitude theta: cos^2 |p_xz|^2 = sin^2 p_y^2 with p_y cos >= 0 (its
    // nappe). Y is monotone on [from, to], so it crosses there at most once.
    std::optional<double> crossY(const FrameRay& ray, double boundary, double from,
                                 double to) const override {
        const double theta = kPi * boundary / height_;
        const double c = std::cos(theta), s = std::sin(theta);
        const glm::dvec3 o = ray.origin, d = ray.dir;
        // The equator's cone is the plane y = 0 (counted twice: the quadratic's double root
        // would lose half the digits).
        if (std::abs(c) < 1e-9) {
            if (d.y == 0.0) return std::nullopt;
            const double t = -o.y / d.y;
            return t >= from && t <= to ? std::optional(t) : std::nullopt;
        }
        const double c2 = c * c, s2 = s * s;
        const double a = c2 * (d.x * d.x + d.z * d.z) - s2 * d.y * d.y;
        const double b = c2 * (o.x * d.x + o.z * d.z) - s2 * o.y * d.y;
        const double k = c2 * (o.x * o.x + o.z * o.z) - s2 * o.y * o.y;
        double roots[2];
        int count = 0;
        if (a == 0.0) {
            if (b != 0.0) roots[count++] = -k / (2.0 * b);
        } else {
            const double disc = b * b - a * k;
            if (disc < 0.0) return std::nullopt;
            const double q = -(b + std::copysign(std::sqrt(disc), b));
            roots[count++] = q / a;
            if (q != 0.0) roots[count++] = k / q;
        }
        std::optional<double> first;
        for (int r = 0; r < count; ++r) {
            const double t = roots[r];
            if (!(t >= from && t <= to)) continue;
            if (ray.at(t).y * c < 0.0) continue;  // the other nappe
            if (!first || t < *first) first = t;
        }
        return first;
    }

    ShellSpan clip(const FrameRay& ray) const override {
        ShellSpan span;
        const glm::dvec2 ball = insideRadius<3>(ray.origin, ray.dir, shellRadius());
        span.tEnter = ball.x;
        span.tExit = ball.y;
        return span;
    }

    glm::dvec3 topNormal(const glm::dvec3& q, const glm::dvec2& g) const override {
        // q = r w(theta, phi) with r = 1 + s h: n = r w - r_theta e_theta -
        // r_phi / sin(theta) e_phi, with r_theta = s H / pi dh/dY, r_phi = s W / 2 pi dh/dX.
        const double r = glm::length(q);
        if (r == 0.0) return {0.0, 1.0, 0.0};
        const glm::dvec3 w = q / r;
        const double sinTheta = std::hypot(w.x, w.z), cosTheta = w.y;
        const glm::dvec2 phi =
            sinTheta > 0.0 ? glm::dvec2(w.x, w.z) / sinTheta : glm::dvec2(0.0, 1.0);
        const glm::dvec3 eTheta(cosTheta * phi.x, -sinTheta, cosTheta * phi.y);
        const glm::dvec3 ePhi(phi.y, 0.0, -phi.x);
        const double rTheta = heightScale_ * height_ / kPi * g.y;
        const double rPhi = heightScale_ * width_ / (2.0 * kPi) * g.x;
        return r * w - rTheta * eTheta - rPhi / std::max(sinTheta, 1e-12) * ePhi;
    }

    glm::dvec3 faceNormal(ShellFace, const FrameRay&) const override { return {0.0, 1.0, 0.0}; }
};

}  // namespace

// The ellipsoid's geometry, the half of its rows that is code (core/base/BaseType.h; the
// data, the ellipsoid's and the sphere's names and sizes, is their //@base lines in
// variants.glsl): radii A, B, C, the frame's scale.
BaseType ellipsoidGeometry() {
    return {
        .kind = BaseKind::Ellipsoid,
        .shaderFile = "base_ellipsoid.glsl",
        .frameScale = [](const BaseShape& b) { return b.radii; },
        // The ball of the shell's radius 1 + top.
        .boxMax = [](const BaseShape& b, int, int, double top) { return b.radii * (1.0 + top); },
        .boxIsSymmetric = true,
        // The geometric mean of a texel's sides on the sphere of the mean radius r:
        // 2 pi r / W around the equator, pi r / H along a meridian.
        .texelSize =
            [](const BaseShape& b, int w, int h) {
                const double r = (b.radii.x + b.radii.y + b.radii.z) / 3.0;
                return std::sqrt(2.0 * kPi * r / w * kPi * r / h);
            },
        // Around the axis W texels span 2 pi at radius 1, along it H texels pi radians.
        .texelsPerFrameUnit = [](int w, int h) { return std::max(w / (2.0 * kPi), h / kPi); },
        // On the equator of the smallest radius r: 2 pi r / W around, pi r / H along.
        .shortestTexelSide =
            [](const BaseShape& b, int w, int h) {
                const double r = std::min({b.radii.x, b.radii.y, b.radii.z});
                return std::min(2.0 * kPi * r / w, kPi * r / h);
            },
        .frameStretchesPastTexels = true,
        // The frame normal r w - (s H / pi) gy e_theta - (s W / 2 pi) gx e_phi / sin theta,
        // at most its parts' sum with sin theta >= 1e-6 (base_ellipsoid.glsl).
        .objectNormalRange =
            [](const BaseShape& b, int w, int h, double s, double maxHeight) {
                const double g = maxHeight, r = 1.0 + s * maxHeight;
                const double around = s * w / (2.0 * kPi) * g, along = s * h / kPi * g;
                return curved::objectNormalRange(b.radii, r + along + around * 1e6);
            },
        .objectPoint =
            [](const BaseShape& b, int w, int h, double s, const glm::dvec2& mapPoint,
               double height) {
                const double phi = curved::angleOf(mapPoint.x, w), radius = 1.0 + s * height;
                const double theta = kPi * (mapPoint.y / h);
                const glm::dvec3 q =
                    radius * glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta),
                                        std::sin(theta) * std::cos(phi));
                return q * b.radii;
            },
        .makeSurface = [](const BaseShape& shape, int w, int h, double s,
                          double maxHeight) -> std::unique_ptr<BaseSurface> {
            return std::make_unique<EllipsoidSurface>(shape, w, h, s, maxHeight);
        },
    };
}

}  // namespace microrelief
