// What microrelief-render says of a mesh it draws on (--base mesh), in the single picture
// and on camera paths alike: with -v its size beside the shell's thickness (what
// --height-scale is measured against: the mesh's units), and, once drawn, its triangles of
// zero area in texture coordinates (docs/scene-and-cli.md, "The mesh base").
#pragma once

#include <string>

#include "microrelief/core/base/TriangleMesh.h"

namespace microrelief {

// -v's line: the mesh `name`'s triangles, vertices, box, diagonal and median triangle, and
// its shell `heightScale` x the map's largest height `top` thick, in mesh units and as a
// share of the diagonal.
std::string meshSizeLine(const std::string& name, const TriangleMesh& mesh, double heightScale,
                         double top);

// Warns (one line) where triangles of `mesh` have zero area in texture coordinates: the map
// is one height or stripes over them, and where every triangle has, no relief shows.
void warnOfZeroUvArea(const std::string& name, const TriangleMesh& mesh);

}  // namespace microrelief
