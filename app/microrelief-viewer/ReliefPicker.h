// Picking: what lies under the cursor, found by the library's CPU twin of the shader's
// traversal (trace/MultilevelTracer.h) along the very ray the pixel's fragment traces
// (CameraFrame::pixelRay), so the answer agrees with the picture.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "microrelief/heightmap/HeightMap.h"
#include "microrelief/render/Camera.h"
#include "microrelief/render/ModelTransform.h"
#include "microrelief/trace/MultilevelTracer.h"

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
    // A new map or height scale; the tracer (its max pyramid) is rebuilt on the next pick.
    void setMap(std::shared_ptr<const HeightMap> map);
    void setHeightScale(double heightScale);
    void setBase(const BaseShape& base);
    void setInterpolation(Interpolation interpolation);
    // The map repeated across the base (--tile).
    void setTiles(glm::ivec2 tiles);
    // The map's samples changed inside `changed` (sculpting): the tracer, if built, takes
    // them from `map` (the same map, edited) and brings its pyramid up to date.
    void mapChanged(std::shared_ptr<const HeightMap> map, const std::vector<TexelRect>& changed);
    // Where the relief sits in the world (the renderer's model transform).
    void setModel(const ModelTransform& model) { model_ = model; }

    // The hit along the ray through pixel (column, row) of `camera`, or nothing.
    std::optional<PickResult> pick(const CameraFrame& camera, int column, int row);

private:
    std::shared_ptr<const HeightMap> map_;
    double heightScale_ = 0.1;
    BaseShape base_;
    Interpolation interpolation_ = Interpolation::Bilinear;
    ModelTransform model_;
    glm::ivec2 tiles_{1, 1};
    std::unique_ptr<MultilevelTracer> tracer_;
};

}  // namespace microrelief
