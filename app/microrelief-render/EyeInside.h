// The scene contract keeps the eye outside the relief's solid; from inside it no picture
// is defined (the methods and the reference disagree on what the rays meet). Asked of the
// exact reference: a ray from inside the solid hits it at t = 0. Single pictures warn of
// it; camera paths sum up the frames it concerns once a run.
#pragma once

#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/gl/HeadlessRender.h"

namespace microrelief {

// Whether `job`'s eye lies inside the solid of `map` (the heights drawn: an animated
// field's as evaluated) over its base, tiles and model. A tiled map whose larger image
// would exceed 2^24 samples is not checked (false).
bool eyeInsideTheSolid(const HeightMap& map, const RenderJob& job);
// The same on the mesh base (ReliefDesc::onMesh): whether `job`'s eye lies inside the
// relief's solid over `mesh` (docs/bases.md, "The mesh": the union of the triangles'
// prisms, between the mesh and the relief's top), `map` addressed as the mesh's classes
// take it (its rows reversed: HeightMap.h's rowsReversed), asked of the exact reference
// (core/trace/MeshReference.h). Not whether it is inside a closed mesh's volume: that is
// no part of the solid, and the picture from there is defined (the mesh seen from behind).
bool eyeInsideTheMeshSolid(const TriangleMesh& mesh, const HeightMap& map, const RenderJob& job);

}  // namespace microrelief
