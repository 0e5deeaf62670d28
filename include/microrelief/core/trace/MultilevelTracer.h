// The multilevel traversal of shaders/microrelief/multilevel_trace.glsl on the CPU: the
// same algorithm over the same max pyramid and the same base-surface seam
// (core/base/BaseSurface.h), step for step (the segment walk is core/trace/SegmentWalk.h's,
// shared with MeshTracer), for engines that need the relief for picking or
// collision queries, and as a twin that tests hold the shader to.
#pragma once

#include <limits>
#include <memory>
#include <optional>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/base/BaseSurface.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/heightmap/SurfacePatch.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/trace/ReferenceTracer.h"

namespace microrelief {

// What the traversal did for one ray: the figures the shader writes to its statistics
// output.
struct TraversalStats {
    int iterations = 0;  // segments visited
    int fetches = 0;     // texels read, pyramid and samples
    int stopLevel = -1;  // pyramid level of the last segment examined
    bool exhausted = false;
};

struct ReliefHit {
    HitFace face = HitFace::Top;
    double t = 0.0;       // ray parameter
    glm::dvec3 position;  // object space (ModelTransform::pointToWorld for the world's)
    glm::dvec3 normal;    // object space, unit, outward (ModelTransform::normalToWorld)
    glm::dvec2 uv;        // map uv
    double height = 0.0;  // h of the hit's map point (the map's value there, on the surface)
};

// What one ray asks of the relief, beside the ray (relief_query.glsl's mr_RayQuery): the
// first point of the closed solid with t in [tMin, tMax] (the start itself when it lies in
// the solid), or with anyHit only whether there is one (the shader then skips the normal;
// here the hit is the same either way, these traversals being near-first).
struct RayQuery {
    double tMin = 0.0;
    double tMax = std::numeric_limits<double>::infinity();
    bool anyHit = false;
};

class MultilevelTracer {
public:
    // Builds the max pyramid of `map` laid over `base`, for the surface `interpolation` makes
    // of it, the map repeated `tiles` times across the base (--tile); the map is copied
    // (the tracer owns its data).
    MultilevelTracer(HeightMap map, double heightScale, const BaseShape& base = {},
                     Interpolation interpolation = Interpolation::Bilinear,
                     glm::ivec2 tiles = {1, 1});

    // The first hit of `ray` with the relief solid, or nothing. The ray is in the relief's
    // object space, where the base shape lies, before any model transform
    // (ModelTransform::toObject of a world ray; t is kept, so the world hit is the world
    // ray at the same t).
    std::optional<ReliefHit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const {
        return intersect(ray, RayQuery{}, stats);
    }
    // The hit `query` asks for.
    std::optional<ReliefHit> intersect(const Ray& ray, const RayQuery& query,
                                       TraversalStats* stats = nullptr) const;

    // After samples of the map changed inside `changed` (a dynamic map: sculpting): the new
    // samples there copied from `map` (the same size), the pyramid brought up to date over
    // them (MaxPyramid::update), the base's shell fitted to the new maximum.
    void mapChanged(const HeightMap& map, const TexelRect& changed);

    const HeightMap& map() const { return map_; }
    const MaxPyramid& pyramid() const { return pyramid_; }
    const BaseSurface& base() const { return *base_; }
    double heightScale() const { return heightScale_; }
    // The iteration budget, as the renderer sets it for this map.
    int maxIterations() const { return maxIterations_; }

    Interpolation interpolation() const { return interpolation_; }

private:
    struct LeafHit {
        double t;
        glm::dvec3 normal;  // in the base's frame (BaseSurface::topNormal)
    };
    // The walk's steps add what they read to the ray's `stats`.
    SurfacePatch patchAt(int i, int j, TraversalStats& stats) const;
    std::optional<LeafHit> intersectLeaf(const FrameRay& ray, double ta, double tb,
                                         TraversalStats& stats) const;
    std::optional<LeafHit> intersectLeafCells(const FrameRay& ray, double ta, double tb,
                                              TraversalStats& stats) const;
    std::optional<LeafHit> walkLeafCells(const FrameRay& ray, double from, double to,
                                         glm::dvec2 branch, TraversalStats& stats) const;
    std::optional<double> cellStretchHit(const FrameRay& ray, const SurfacePatch& patch, double c0,
                                         double c1) const;
    // The frame ray from the shell's entry as the path of the shared segment walk
    // (core/trace/SegmentWalk.h).
    class FramePath;
    glm::dvec3 topNormal(const SurfacePatch& patch, const glm::dvec3& framePoint) const;

    HeightMap map_;
    Interpolation interpolation_;
    MapAddressing addressing_;
    int width_, height_;  // the whole map's, tiles included
    MaxPyramid pyramid_;
    double heightScale_;
    std::unique_ptr<BaseSurface> base_;
    int maxIterations_;
};

// The budget a traversal of a W x H map gets, shared by the renderer and the CPU twin:
// a ray visits about two segments per finest texel it crosses plus their ancestors, so
// 8 (W + H) + 256 is several times what any ray needs; running out means a bug.
int traversalBudget(int width, int height);

}  // namespace microrelief
