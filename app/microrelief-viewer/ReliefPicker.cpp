#include "ReliefPicker.h"

namespace microrelief {

void ReliefPicker::setMap(std::shared_ptr<const HeightMap> map) {
    map_ = std::move(map);
    tracer_.reset();
}

void ReliefPicker::mapChanged(std::shared_ptr<const HeightMap> map,
                              const std::vector<TexelRect>& changed) {
    map_ = std::move(map);
    if (!tracer_) return;  // built from the edited map when it is next needed
    for (const TexelRect& rect : changed) tracer_->mapChanged(*map_, rect);
}

void ReliefPicker::setHeightScale(double heightScale) {
    if (heightScale == heightScale_) return;
    heightScale_ = heightScale;
    tracer_.reset();
}

void ReliefPicker::setBase(const BaseShape& base) {
    if (base == base_) return;
    base_ = base;
    tracer_.reset();
}

void ReliefPicker::setTiles(glm::ivec2 tiles) {
    if (tiles == tiles_) return;
    tiles_ = tiles;
    tracer_.reset();
}

void ReliefPicker::setInterpolation(Interpolation interpolation) {
    if (interpolation == interpolation_) return;
    interpolation_ = interpolation;
    tracer_.reset();
}

std::optional<PickResult> ReliefPicker::pick(const CameraFrame& camera, int column, int row) {
    if (!map_ || column < 0 || row < 0 || column >= camera.width || row >= camera.height)
        return std::nullopt;
    // Built lazily: dragging the height-scale slider must not rebuild the pyramid for
    // every intermediate value.
    if (!tracer_)
        tracer_ =
            std::make_unique<MultilevelTracer>(*map_, heightScale_, base_, interpolation_, tiles_);
    TraversalStats stats;
    // In the relief's object space, where the twin works; t is the world ray's.
    const Ray ray = camera.pixelRay(column, row);
    const std::optional<ReliefHit> hit = tracer_->intersect(model_.toObject(ray), &stats);
    if (!hit) return std::nullopt;
    return PickResult{hit->uv, hit->height, ray.origin + hit->t * ray.direction, hit->face,
                      stats.iterations};
}

}  // namespace microrelief
