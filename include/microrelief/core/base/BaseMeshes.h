// The analytic bases written as triangle meshes (docs/bases.md, "The mesh"): a grid over the
// plane's footprint and a tube over the cylinder's side, each vertex placed, with its normal
// and texture coordinate, where the base's own mapping puts that (u, v). What the tests hold
// the mesh base to the analytic ones with (a flat grid is the plane exactly; a tube of many
// sides is the cylinder to its chords) and what the benchmark measures a mesh against them on.
//
// use:      TriangleMesh grid = planeGridMesh(8, 1.0f, 0.5f);    // 8 x 8 quads, 128 triangles
//           TriangleMesh side = cylinderTubeMesh(96, 8, 0.5f, 2.0f);
#pragma once

#include <glm/glm.hpp>

#include "microrelief/core/base/TriangleMesh.h"

namespace microrelief {

// n x n quads on y = 0 over the plane base's footprint for a map of aspect a : b
// (BaseShape.h: x = (u - 0.5) a, z = (v - 0.5) b), normals +y, each vertex's texture
// coordinate uvOffset + (u, v) * uvScale, u = i / n and v = j / n at vertex (i, j): with the
// defaults, the plane base's own (u, v). Two triangles a quad, counter-clockwise seen from +y.
// With a, b and 1 / n powers of two every float here is exact.
TriangleMesh planeGridMesh(int n, float a, float b, glm::vec2 uvOffset = glm::vec2(0.0f),
                           glm::vec2 uvScale = glm::vec2(1.0f));

// A tube about the y axis as the cylinder base maps its side (BaseShape.h): `around` x
// `along` quads, vertex (k, j) at u = k / around, the angle phi = 2 pi (u - 1/2), and
// v = j / along, at y = (1 - 2 v) L / 2 and R (sin phi, *, cos phi); the column u = 1 a copy of
// u = 0 (the seam). Normals the cylinder's, or their opposites (`inward`: then with R a power
// of two each position is exactly -R times its float normal, so that the tube's normal lines
// meet on the axis, a focal line at t = R / s). Outward, triangles face out.
TriangleMesh cylinderTubeMesh(int around, int along, float radius, float length,
                              bool inward = false);

}  // namespace microrelief
