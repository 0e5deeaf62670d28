#include "EyeInside.h"

#include "microrelief/core/trace/MeshReference.h"
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

bool eyeInsideTheMeshSolid(const TriangleMesh& mesh, const HeightMap& map, const RenderJob& job) {
    const MeshReference reference(mesh, map, job.heightScale, job.interpolation);
    const MeshHit hit = reference.trace(Ray{job.camera.eye, job.camera.target - job.camera.eye});
    return hit.surface == MeshSurface::Inside;
}

}  // namespace microrelief
