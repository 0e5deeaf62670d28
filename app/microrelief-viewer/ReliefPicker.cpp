#include "ReliefPicker.h"

namespace microrelief {

void ReliefPicker::apply(const ReliefDesc& relief, std::shared_ptr<const HeightMap> heights) {
    // What the twin is built from (core/trace/MultilevelTracer.h); the model only moves rays.
    if (heights != map_ || relief.heightScale != relief_.heightScale || relief.base != relief_.base ||
        relief.interpolation != relief_.interpolation || relief.tiles != relief_.tiles)
        tracer_.reset();
    map_ = std::move(heights);
    relief_ = relief;
}

void ReliefPicker::mapChanged(std::shared_ptr<const HeightMap> map,
                              const std::vector<TexelRect>& changed) {
    map_ = std::move(map);
    if (!tracer_) return;  // built from the edited map when it is next needed
    for (const TexelRect& rect : changed) tracer_->mapChanged(*map_, rect);
}

std::optional<PickResult> ReliefPicker::pick(const CameraFrame& camera, int column, int row) {
    if (!map_ || column < 0 || row < 0 || column >= camera.width || row >= camera.height)
        return std::nullopt;
    // Built lazily: dragging the height-scale slider must not rebuild the pyramid for
    // every intermediate value.
    if (!tracer_) {
        tracer_ = std::make_unique<MultilevelTracer>(*map_, relief_.heightScale, relief_.base,
                                                     relief_.interpolation, relief_.tiles);
        ++tracersBuilt_;
    }
    TraversalStats stats;
    // In the relief's object space, where the twin works; t is the world ray's.
    const Ray ray = camera.pixelRay(column, row);
    const std::optional<ReliefHit> hit = tracer_->intersect(relief_.model.toObject(ray), &stats);
    if (!hit) return std::nullopt;
    return PickResult{hit->uv, hit->height, ray.origin + hit->t * ray.direction, hit->face,
                      stats.iterations};
}

}  // namespace microrelief
