// The cylinder base (BaseShape.h): a column of radius 1 in the frame, axis y, flat caps at y = +-1.
// shaders/microrelief/base_cylinder.glsl is the shader's copy.
#include <algorithm>
#include <cmath>

#include "core/base/CurvedCommon.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"

namespace microrelief {

namespace {

using curved::insideRadius;
using curved::kPi;

// The cylinder: radius 1 in the frame, axis y, caps at y = +-1.
class CylinderSurface final : public CurvedSurface {
public:
    using CurvedSurface::CurvedSurface;

    glm::dvec2 insideRadial(const FrameRay& ray, double r) const override {
        return insideRadius<2>(glm::dvec2(ray.origin.x, ray.origin.z),
                               glm::dvec2(ray.dir.x, ray.dir.z), r);
    }
    double radial(const glm::dvec3& q) const override { return std::hypot(q.x, q.z); }
    double mapY(const glm::dvec3& q) const override { return height_ * 0.5 * (1.0 - q.y); }

    double lowestRadial(const FrameRay& ray, double ta, double tb) const override {
        // |p_xz(t)| is convex: its minimum over [ta, tb] is at the nearest point, clamped.
        const glm::dvec2 o(ray.origin.x, ray.origin.z), d(ray.dir.x, ray.dir.z);
        const double dd = glm::dot(d, d);
        const double t = dd > 0.0 ? std::clamp(-glm::dot(o, d) / dd, ta, tb) : ta;
        return glm::length(o + t * d);
    }

    glm::dvec2 rangeY(const FrameRay& ray, double ta, double tb) const override {
        const double ya = mapY(ray.at(ta)), yb = mapY(ray.at(tb));  // linear in t
        return {std::min(ya, yb), std::max(ya, yb)};
    }
    std::optional<double> turnY(const FrameRay&) const override { return std::nullopt; }

    // The plane y = 1 - 2 Y / H, which the line crosses once.
    std::optional<double> crossY(const FrameRay& ray, double boundary, double,
                                 double) const override {
        if (ray.dir.y == 0.0) return std::nullopt;
        return (1.0 - 2.0 * boundary / height_ - ray.origin.y) / ray.dir.y;
    }

    // The slab |y| <= 1 and the cylinder of the shell's radius: a convex region, so one
    // interval; the later of the two entries names the face.
    ShellSpan clip(const FrameRay& ray) const override {
        ShellSpan span;
        const glm::dvec2 side = insideRadius<2>(glm::dvec2(ray.origin.x, ray.origin.z),
                                                glm::dvec2(ray.dir.x, ray.dir.z), shellRadius());
        if (side.x > side.y) return {};
        glm::dvec2 slab(-HUGE_VAL, HUGE_VAL);
        ShellFace cap = ShellFace::None;
        if (ray.dir.y == 0.0) {
            if (std::abs(ray.origin.y) > 1.0) return {};
        } else {
            const double t0 = (-1.0 - ray.origin.y) / ray.dir.y,
                         t1 = (1.0 - ray.origin.y) / ray.dir.y;
            slab = {std::min(t0, t1), std::max(t0, t1)};
            cap = ray.dir.y > 0.0 ? ShellFace::CapBottom : ShellFace::CapTop;
        }
        span.tEnter = std::max(side.x, slab.x);
        span.tExit = std::min(side.y, slab.y);
        span.entry = slab.x > side.x ? cap : ShellFace::None;
        return span;
    }

    glm::dvec3 topNormal(const glm::dvec3& q, const glm::dvec2& g) const override {
        // q = rho e_rho(phi) + y e_y with rho = 1 + s h: n = rho e_rho - rho_phi e_phi -
        // rho rho_y e_y, with rho_phi = s W / 2 pi dh/dX and rho_y = -s H / 2 dh/dY.
        const double rho = radial(q);
        if (rho == 0.0) return {0.0, 1.0, 0.0};
        const glm::dvec3 eRho(q.x / rho, 0.0, q.z / rho), ePhi(q.z / rho, 0.0, -q.x / rho);
        const double rhoPhi = heightScale_ * width_ / (2.0 * kPi) * g.x;
        const double rhoY = -heightScale_ * height_ * 0.5 * g.y;
        return rho * eRho - rhoPhi * ePhi - rho * rhoY * glm::dvec3(0.0, 1.0, 0.0);
    }

    glm::dvec3 faceNormal(ShellFace face, const FrameRay&) const override {
        return {0.0, face == ShellFace::CapTop ? 1.0 : -1.0, 0.0};
    }
};

}  // namespace

namespace {

// The frame's scale: radius R and half the length L / 2 (the frame's axis spans y = +-1).
glm::dvec3 cylinderFrame(const BaseShape& b) {
    return {b.radius, 0.5 * b.length, b.radius};
}

}  // namespace

// The cylinder's geometry, the half of its rows that is code (core/base/BaseType.h; the
// data, its name and sizes R and L, is its //@base line in variants.glsl).
BaseType cylinderGeometry() {
    return {
        .kind = BaseKind::Cylinder,
        .shaderFile = "base_cylinder.glsl",
        .frameScale = [](const BaseShape& b) { return cylinderFrame(b); },
        // The column of the shell's radius 1 + top between the caps.
        .boxMax =
            [](const BaseShape& b, int, int, double top) {
                return cylinderFrame(b) * glm::dvec3(1.0 + top, 1.0, 1.0 + top);
            },
        .boxIsSymmetric = true,
        // The geometric mean of a texel's sides on the base: 2 pi R / W around, L / H along.
        .texelSize = [](const BaseShape& b, int w,
                        int h) { return std::sqrt(2.0 * kPi * b.radius / w * b.length / h); },
        // Around the axis W texels span 2 pi at radius 1, along it H texels span 2 units.
        .texelsPerFrameUnit = [](int w, int h) { return std::max(w / (2.0 * kPi), 0.5 * h); },
        // 2 pi R / W around, L / H along.
        .shortestTexelSide =
            [](const BaseShape& b, int w, int h) {
                return std::min(2.0 * kPi * b.radius / w, b.length / h);
            },
        .frameStretchesPastTexels = false,
        // The frame normal r w - (s W / 2 pi) gx e_phi - (s H / 2) gy e_y, at most
        // r (1 + along) + around (base_cylinder.glsl, mr_baseTopNormal).
        .objectNormalRange =
            [](const BaseShape& b, int w, int h, double s, double maxHeight) {
                const double g = maxHeight, r = 1.0 + s * maxHeight;
                const double around = s * w / (2.0 * kPi) * g, along = s * h / 2.0 * g;
                return curved::objectNormalRange(cylinderFrame(b), r * (1.0 + along) + around);
            },
        .objectPoint =
            [](const BaseShape& b, int w, int h, double s, const glm::dvec2& mapPoint,
               double height) {
                const double phi = curved::angleOf(mapPoint.x, w), radius = 1.0 + s * height;
                const glm::dvec3 q(radius * std::sin(phi), 1.0 - 2.0 * (mapPoint.y / h),
                                   radius * std::cos(phi));
                return q * cylinderFrame(b);
            },
        .makeSurface = [](const BaseShape& shape, int w, int h, double s,
                          double maxHeight) -> std::unique_ptr<BaseSurface> {
            return std::make_unique<CylinderSurface>(shape, w, h, s, maxHeight);
        },
    };
}

}  // namespace microrelief
