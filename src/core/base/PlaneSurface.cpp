// The plane y = 0 (scene-and-cli.md, "Height map to surface"): its frame is map space,
// where the ray stays a straight line in (X, Y, h) (map_space.glsl), so a segment's
// footprint is the rectangle of its ends and its lowest height the lower end.
// shaders/microrelief/base_plane.glsl is the shader's copy.
#include <algorithm>
#include <cmath>
#include <limits>

#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/base/BaseType.h"

namespace microrelief {

namespace {

class PlaneSurface final : public BaseSurface {
public:
    using BaseSurface::BaseSurface;

    double texelsPerUnit() const { return std::max(width_, height_); }

    FrameRay frameRay(const Ray& world) const override {
        const double k = texelsPerUnit();
        return {{world.origin.x * k + 0.5 * width_, world.origin.z * k + 0.5 * height_,
                 world.origin.y / heightScale_},
                {world.direction.x * k, world.direction.z * k, world.direction.y / heightScale_}};
    }

    glm::dvec3 mapPoint(const glm::dvec3& q) const override { return q; }

    // The box [0, W] x [0, H] x [0, maxHeight]; the slab the entry crosses names the face.
    ShellSpan clip(const FrameRay& ray) const override {
        const glm::dvec3 lo(0.0), hi(width_, height_, maxHeight_);
        ShellSpan span;
        span.tEnter = -std::numeric_limits<double>::max();
        span.tExit = std::numeric_limits<double>::max();
        int entryAxis = -1, exitAxis = -1;
        for (int axis = 0; axis < 3; ++axis) {
            if (ray.dir[axis] == 0.0) {
                if (ray.origin[axis] < lo[axis] || ray.origin[axis] > hi[axis]) return {};
                continue;
            }
            double t0 = (lo[axis] - ray.origin[axis]) / ray.dir[axis];
            double t1 = (hi[axis] - ray.origin[axis]) / ray.dir[axis];
            if (t0 > t1) std::swap(t0, t1);
            if (t0 > span.tEnter) {
                span.tEnter = t0;
                entryAxis = axis;
            }
            if (t1 < span.tExit) {
                span.tExit = t1;
                exitAxis = axis;
            }
        }
        // Entering through the top face (going down) is the traversal's question.
        if (entryAxis == 0) span.entry = ShellFace::WallX;
        if (entryAxis == 1) span.entry = ShellFace::WallY;
        if (entryAxis == 2 && ray.dir.z > 0.0) span.entry = ShellFace::Bottom;
        span.floorExit = exitAxis == 2 && ray.dir.z < 0.0;
        return span;
    }

    Footprint footprint(const FrameRay& ray, double ta, double tb) const override {
        const glm::dvec3 pa = ray.at(ta), pb = ray.at(tb);
        return {glm::min(glm::dvec2(pa), glm::dvec2(pb)), glm::max(glm::dvec2(pa), glm::dvec2(pb)),
                std::min(pa.z, pb.z), std::abs(pb.z - pa.z)};
    }

    double lowest(const FrameRay& ray, double ta, double tb) const override {
        return std::min(ray.at(ta).z, ray.at(tb).z);
    }

    double descendTo(const FrameRay& ray, double ta, double tb, double h) const override {
        return ray.dir.z < 0.0 ? std::clamp((h - ray.origin.z) / ray.dir.z, ta, tb) : ta;
    }

    glm::dvec3 topNormal(const glm::dvec3&, const glm::dvec2& gradient) const override {
        return {-gradient.x, -gradient.y, 1.0};
    }

    glm::dvec3 faceNormal(ShellFace face, const FrameRay& ray) const override {
        const int axis = face == ShellFace::WallX ? 0 : face == ShellFace::WallY ? 1 : 2;
        glm::dvec3 n(0.0);
        n[axis] = ray.dir[axis] > 0.0 ? -1.0 : 1.0;
        return n;
    }

    std::optional<double> crossX(const FrameRay& ray, double boundary, double) const override {
        if (ray.dir.x == 0.0) return std::nullopt;
        return (boundary - ray.origin.x) / ray.dir.x;
    }
    bool xIncreases(const FrameRay& ray) const override { return ray.dir.x > 0.0; }
    double mapY(const glm::dvec3& q) const override { return q.y; }
    std::optional<double> turnY(const FrameRay&) const override { return std::nullopt; }
    std::optional<double> crossY(const FrameRay& ray, double boundary, double,
                                 double) const override {
        if (ray.dir.y == 0.0) return std::nullopt;
        return (boundary - ray.origin.y) / ray.dir.y;
    }
    double finalLength() const override { return std::numeric_limits<double>::infinity(); }

    // Map (X, Y, h) -> world (x, z, y): the inverse transpose of the map's scales.
    glm::dvec3 worldNormal(const glm::dvec3& n) const override {
        const double k = texelsPerUnit();
        return glm::normalize(glm::dvec3(n.x * k, n.z / heightScale_, n.y * k));
    }
};

}  // namespace

// The plane's geometry, the half of its rows that is code (core/base/BaseType.h; the data,
// its name and sizes, is its //@base line in variants.glsl). Its frame is the world's, the
// map's longer side one unit: T = max(W, H) texels a unit.
BaseType planeGeometry() {
    return {
        .kind = BaseKind::Plane,
        .shaderFile = "base_plane.glsl",
        .frameScale = [](const BaseShape&) { return glm::dvec3(1.0); },
        // From y = 0 (the base) to the top, over the map's rectangle.
        .boxMax =
            [](const BaseShape&, int w, int h, double top) {
                const double longer = std::max(w, h);
                return glm::dvec3(0.5 * w / longer, top, 0.5 * h / longer);
            },
        .boxIsSymmetric = false,
        .texelSize = [](const BaseShape&, int w, int h) { return 1.0 / std::max(w, h); },
        .texelsPerFrameUnit = [](int w, int h) { return double(std::max(w, h)); },
        .shortestTexelSide = [](const BaseShape&, int w, int h) { return 1.0 / std::max(w, h); },
        .frameStretchesPastTexels = false,
        // Top (-gx T, 1 / s, -gy T) with |g| <= max h a texel along each axis; walls T and
        // the bottom 1 / s along one axis (base_plane.glsl, mr_baseObjectNormal).
        .objectNormalRange =
            [](const BaseShape&, int w, int h, double s, double maxHeight) {
                const double t = std::max(w, h);
                return std::pair{std::min(t, 1.0 / s),
                                 std::max(std::sqrt(2.0) * maxHeight * t + 1.0 / s, t)};
            },
        .objectPoint =
            [](const BaseShape&, int w, int h, double s, const glm::dvec2& mapPoint,
               double height) {
                const double side = std::max(w, h);
                return glm::dvec3((mapPoint.x / w - 0.5) * w / side, s * height,
                                  (mapPoint.y / h - 0.5) * h / side);
            },
        .makeSurface = [](const BaseShape& shape, int w, int h, double s,
                          double maxHeight) -> std::unique_ptr<BaseSurface> {
            return std::make_unique<PlaneSurface>(shape, w, h, s, maxHeight);
        },
    };
}

}  // namespace microrelief
