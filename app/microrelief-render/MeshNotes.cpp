#include "MeshNotes.h"

#include "SceneOptions.h"
#include "microrelief/core/Log.h"
#include "microrelief/core/Text.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/io/MeshFile.h"

namespace microrelief {

std::string meshSizeLine(const std::string& name, const TriangleMesh& mesh, double heightScale,
                         double top) {
    const MeshSize size = meshSize(mesh);
    return name + ": " + std::to_string(mesh.triangleCount()) + " triangles, " +
           std::to_string(mesh.vertexCount()) + " vertices, box " + exactVector(size.low) +
           " to " + exactVector(size.high) + " (diagonal " + formatNumber(size.diagonal, 4) +
           ", median triangle " + formatNumber(size.medianTriangle, 4) + "); the shell " +
           flagName("heightScale") + " " + formatNumber(heightScale, 4) +
           " x the map's largest height " + formatNumber(top, 4) + " = " +
           formatNumber(heightScale * top, 4) + " mesh units thick (" +
           formatNumber(100.0 * heightScale * top / size.diagonal, 3) + " % of the diagonal)";
}

void warnOfZeroUvArea(const std::string& name, const TriangleMesh& mesh) {
    if (const std::size_t flat = zeroUvAreaTriangles(mesh); flat > 0)
        logWarning(name + ": " + std::to_string(flat) + " of " +
                   std::to_string(mesh.triangleCount()) +
                   " triangles have zero area in texture coordinates (their uvs on one point "
                   "or one line): the map is one height or stripes over them" +
                   (flat == mesh.triangleCount() ? ", and no relief shows anywhere" : ""));
}

}  // namespace microrelief
