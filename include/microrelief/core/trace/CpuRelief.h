// A relief on the CPU, built from the description the renderer draws (core/scene/Scene.h:
// ReliefDesc) over its heights: the twin of the shader's traversal (MultilevelTracer) placed
// by the relief's model transform, so that world rays go in and world hits come out. What a
// host picks with (the viewer's cursor, an engine's collision query): along the very ray a
// pixel's fragment traces (CameraFrame::pixelRay), its answer agrees with the picture.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/core/trace/MultilevelTracer.h"

namespace microrelief {

// A hit in the world.
struct WorldHit {
    double t = 0.0;         // along the world ray, in units of its direction's length
    glm::dvec3 position;    // world: origin + t direction
    glm::dvec3 normal;      // world, unit, outward (the model's inverse transpose)
    glm::dvec2 uv;          // map uv (v = 0 at the map's first row)
    double height = 0.0;    // the map's value h(u, v) there
    HitFace face = HitFace::Top;
    int iterations = 0;     // segments the traversal visited
};

class CpuRelief {
public:
    // The relief `relief` describes, over `heights` (the samples its map names). The twin
    // (its max pyramid) is built again, at the next query, only for other heights, height
    // scale, base, last level or tiles; the model is applied as it is; the albedo, the
    // animation and its time change nothing (an animated field's heights are the caller's
    // to give).
    void apply(const ReliefDesc& relief, std::shared_ptr<const HeightMap> heights);
    // The map's samples changed inside `changed` (sculpting): the twin, if built, takes them
    // from `map` (the same map, edited) and brings its pyramid up to date.
    void mapChanged(std::shared_ptr<const HeightMap> map, const std::vector<TexelRect>& changed);

    // The first hit of the world ray `world` that `query` asks for (t in the world ray's
    // units), or nothing; nothing before apply().
    std::optional<WorldHit> intersect(const Ray& world, const RayQuery& query = {});
    // The hit along the ray through pixel (column, row) of `camera`, or nothing (a pixel
    // outside the picture too).
    std::optional<WorldHit> pick(const CameraFrame& camera, int column, int row);

    // Twins built so far: a test holds the relief to building only for what changed.
    int twinsBuilt() const { return twinsBuilt_; }

private:
    std::shared_ptr<const HeightMap> map_;
    ReliefDesc relief_;
    std::unique_ptr<MultilevelTracer> twin_;
    int twinsBuilt_ = 0;
};

}  // namespace microrelief
