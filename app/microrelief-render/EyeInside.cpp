#include "EyeInside.h"

#include "microrelief/core/trace/ReferenceTracer.h"

namespace microrelief {

bool eyeInsideTheSolid(const HeightMap& map, const RenderJob& job) {
    const Camera& camera = job.camera;
    // A tiled map from its larger image, where that is not too large to make.
    const bool tiled = job.tiles != glm::ivec2(1, 1);
    if (tiled && map.samples.size() * job.tiles.x * job.tiles.y > (std::size_t(1) << 24))
        return false;
    const HeightMap whole = tiled ? repeatMap(map, job.tiles.x, job.tiles.y) : HeightMap();
    const ReferenceHit hit = traceReference(
        {tiled ? &whole : &map, job.heightScale, job.base, job.interpolation, job.model},
        Ray{camera.eye, camera.target - camera.eye});
    return hit && hit.t == 0.0;
}

}  // namespace microrelief
