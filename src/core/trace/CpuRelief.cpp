#include "microrelief/core/trace/CpuRelief.h"

#include <utility>

namespace microrelief {

void CpuRelief::apply(const ReliefDesc& relief, std::shared_ptr<const HeightMap> heights) {
    // What the twin is built from (MultilevelTracer's constructor); the model only moves rays.
    if (heights != map_ || relief.heightScale != relief_.heightScale ||
        relief.base != relief_.base || relief.interpolation != relief_.interpolation ||
        relief.tiles != relief_.tiles)
        twin_.reset();
    map_ = std::move(heights);
    relief_ = relief;
}

void CpuRelief::mapChanged(std::shared_ptr<const HeightMap> map,
                           const std::vector<TexelRect>& changed) {
    map_ = std::move(map);
    if (!twin_) return;  // built from the edited map when it is next needed
    for (const TexelRect& rect : changed) twin_->mapChanged(*map_, rect);
}

std::optional<WorldHit> CpuRelief::intersect(const Ray& world, const RayQuery& query) {
    if (!map_) return std::nullopt;
    // Built lazily: a host dragging the height scale must not rebuild the pyramid for every
    // value it passes.
    if (!twin_) {
        twin_ = std::make_unique<MultilevelTracer>(*map_, relief_.heightScale, relief_.base,
                                                   relief_.interpolation, relief_.tiles);
        ++twinsBuilt_;
    }
    TraversalStats stats;
    // In the relief's object space, where the twin works: the model is affine, so t is the
    // world ray's (ModelTransform::toObject keeps the parameter).
    const std::optional<ReliefHit> hit =
        twin_->intersect(relief_.model.toObject(world), query, &stats);
    if (!hit) return std::nullopt;
    return WorldHit{hit->t,      world.origin + hit->t * world.direction,
                    relief_.model.normalToWorld(hit->normal),
                    hit->uv,     hit->height,
                    hit->face,   stats.iterations};
}

std::optional<WorldHit> CpuRelief::pick(const CameraFrame& camera, int column, int row) {
    if (column < 0 || row < 0 || column >= camera.width || row >= camera.height)
        return std::nullopt;
    return intersect(camera.pixelRay(column, row));
}

}  // namespace microrelief
