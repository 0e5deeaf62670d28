// Picking: what lies under the cursor, found by the library's CPU twin of the shader's
// traversal (core/trace/MultilevelTracer.h) along the very ray the pixel's fragment traces
// (CameraFrame::pixelRay), so the answer agrees with the picture.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/ModelTransform.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/core/trace/MultilevelTracer.h"

namespace microrelief {

struct PickResult {
    glm::dvec2 uv;        // map uv of the hit
    double height = 0.0;  // the map's value h(u, v) there
    glm::dvec3 position;  // world
    HitFace face = HitFace::Top;
    int iterations = 0;  // segments the traversal visited
};

class ReliefPicker {
public:
    // The relief `relief` describes, over `heights` (the samples its map names, as the
    // viewer holds them). The tracer (its max pyramid) is built again on the next pick only
    // for other heights, height scale, base, last level or tiles; the model is applied as
    // it is.
    void apply(const ReliefDesc& relief, std::shared_ptr<const HeightMap> heights);
    // The map's samples changed inside `changed` (sculpting): the tracer, if built, takes
    // them from `map` (the same map, edited) and brings its pyramid up to date.
    void mapChanged(std::shared_ptr<const HeightMap> map, const std::vector<TexelRect>& changed);

    // The hit along the ray through pixel (column, row) of `camera`, or nothing.
    std::optional<PickResult> pick(const CameraFrame& camera, int column, int row);
    // Tracers built so far: a test holds the picker to building only for what changed.
    int tracersBuilt() const { return tracersBuilt_; }

private:
    std::shared_ptr<const HeightMap> map_;
    ReliefDesc relief_;
    std::unique_ptr<MultilevelTracer> tracer_;
    int tracersBuilt_ = 0;
};

}  // namespace microrelief
