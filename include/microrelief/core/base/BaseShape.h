// The base surface of the paper (section II: "planes, ellipsoids, or cylinders"), as the
// scene contract has it (scene-and-cli.md, "Base surfaces"): a canonical shape scaled by
// its size, the paper's geometric transformation M, and the height map laid over it.
//
//  * plane: y = 0, x = (u - 0.5) a, z = (v - 0.5) b, the longer side one unit; y = s h.
//  * cylinder, radius R, length L, axis y: canonical q = (x / R, 2 y / L, z / R);
//    u = fract(0.5 + atan2(q.x, q.z) / 2 pi), v = (1 - q.y) / 2; the solid
//    { |q.y| <= 1, |q.xz| <= 1 + s h(u, v) }: a column with flat caps.
//  * ellipsoid, radii A, B, C: q = (x / A, y / B, z / C); u as for the cylinder,
//    v = acos(q.y / |q|) / pi; the star-shaped solid { |q| <= 1 + s h(u, v) }.
//    A sphere of radius R is the ellipsoid R, R, R.
// On a curved base s (--height-scale) is a fraction of the canonical radius 1, and u
// wraps: the surface joins column W - 1 to column 0 across the seam u = 0 (at -z).
//
// This file is the description and its world-space geometry (the frame, the bounding
// box, a texel's size); the traversal's seam is core/base/BaseSurface.h.
#pragma once

#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "microrelief/core/GlslConstants.h"

namespace microrelief {

// The kinds of base, one enumerator for each MR_BASE_* of shaders/microrelief/variants.glsl,
// with its value (MICRORELIEF_BASE), generated from it (glsl::MICRORELIEF_GLSL_BASE_KIND_MEMBERS):
// Plane = 0, Cylinder = 1, Ellipsoid = 2 today; MR_BASE_FOO_BAR would be FooBar.
#define MICRORELIEF_BASE_KIND_ENUMERATOR(Name, name, value) Name = value,
enum class BaseKind { MICRORELIEF_GLSL_BASE_KIND_MEMBERS(MICRORELIEF_BASE_KIND_ENUMERATOR) };
#undef MICRORELIEF_BASE_KIND_ENUMERATOR

// Number `i` of the default of row `base`'s size that sets BaseShape's `member`, as
// variants.glsl's //@size line gives it (glsl::kBaseRows), so that BaseShape's defaults
// below are the table's, written once. Used for constants only: a row or a size it does
// not find is a throw, which stops the build at the constant.
constexpr double baseRowDefault(std::string_view base, std::string_view member, int i = 0) {
    for (const glsl::BaseRow& row : glsl::kBaseRows) {
        if (std::string_view(row.name) != base) continue;
        for (int k = 0; k < row.sizeCount; ++k) {
            const glsl::BaseSizeRow& size = row.sizes[k];
            if (std::string_view(size.member) == member) return size.defaults[size.count == 1 ? 0 : i];
        }
    }
    throw "baseRowDefault: no such row of variants.glsl, or no size of it sets that member";
}

// The rows' defaults that BaseShape's members and factories take.
inline constexpr double kCylinderRadius = baseRowDefault("cylinder", "radius");
inline constexpr double kCylinderLength = baseRowDefault("cylinder", "length");
inline constexpr double kEllipsoidRadii[3] = {baseRowDefault("ellipsoid", "radii", 0),
                                              baseRowDefault("ellipsoid", "radii", 1),
                                              baseRowDefault("ellipsoid", "radii", 2)};
inline constexpr double kSphereRadius = baseRowDefault("sphere", "radii");

struct BaseShape {
    BaseKind kind = BaseKind::Plane;
    double radius = kCylinderRadius;  // cylinder (--radius)
    double length = kCylinderLength;  // cylinder (--length)
    glm::dvec3 radii{kEllipsoidRadii[0], kEllipsoidRadii[1],
                     kEllipsoidRadii[2]};  // ellipsoid (--radii; --base sphere --radius R)

    static BaseShape plane() { return {}; }
    static BaseShape cylinder(double radius = kCylinderRadius, double length = kCylinderLength);
    static BaseShape ellipsoid(const glm::dvec3& radii = glm::dvec3{kEllipsoidRadii[0], kEllipsoidRadii[1],
                                                                    kEllipsoidRadii[2]});
    static BaseShape sphere(double radius = kSphereRadius) { return ellipsoid(glm::dvec3(radius)); }

    bool curved() const { return kind != BaseKind::Plane; }
    // Whether u is periodic (the curved bases): the map wraps across u = 0.
    bool wrapsU() const { return curved(); }

    // World size of the canonical frame's unit along x, y, z: (R, L/2, R), (A, B, C), or
    // 1 for the plane (whose frame is the world's). world = scale * q.
    glm::dvec3 frameScale() const;

    // Half the size of the world-space bounding box of the relief, centred at the origin,
    // for a largest height `topHeight` (s max h): the spec's proxy geometry. The plane's
    // box spans y in [0, topHeight] (see boxMin / boxMax).
    glm::dvec3 boxMin(int mapWidth, int mapHeight, double topHeight) const;
    glm::dvec3 boxMax(int mapWidth, int mapHeight, double topHeight) const;

    // The world size of one texel, the unit positions are compared in (issue 11):
    // 1 / max(W, H) on the plane; sqrt(2 pi R / W * L / H) on a cylinder;
    // sqrt(2 pi r / W * pi r / H) on an ellipsoid of mean radius r = (A + B + C) / 3.
    double texelSize(int mapWidth, int mapHeight) const;

    bool operator==(const BaseShape&) const = default;
};

// "plane", "cylinder", "ellipsoid", "sphere" (the ellipsoid with equal radii): the
// --base names. Throws Error(BadInput) for an unknown name.
BaseKind parseBaseKind(const std::string& name);
// The --base name of a shape: "sphere" for an ellipsoid whose radii are equal.
std::string baseName(const BaseShape& shape);

// Throws Error(BadInput), naming the flag, for a size that is zero, negative or not
// finite.
void validateBaseShape(const BaseShape& shape);

}  // namespace microrelief
