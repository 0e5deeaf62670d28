#include "ReliefPicker.h"

namespace microrelief {

void ReliefPicker::setMap(std::shared_ptr<const HeightMap> map) {
    map_ = std::move(map);
    tracer_.reset();
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
        tracer_ = std::make_unique<MultilevelTracer>(*map_, heightScale_, base_, interpolation_);
    TraversalStats stats;
    const std::optional<ReliefHit> hit = tracer_->intersect(camera.pixelRay(column, row), &stats);
    if (!hit) return std::nullopt;
    return PickResult{hit->uv, hit->height, hit->position, hit->face, stats.iterations};
}

}  // namespace microrelief
