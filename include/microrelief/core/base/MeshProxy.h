// The proxy of the mesh base (docs/bases.md, "The mesh", "The proxy"; issue 50): the
// triangles a rasteriser draws so that every ray meeting the relief's solid produces a
// fragment of the prism that holds its first hit. The fragment shader then traces that
// ray in that one prism and writes the hit's depth; the depth test keeps the least over
// the prisms, which is the exact first hit, since the union's first point along a ray is
// the least of the prisms' first points.
//
// use:      MeshProxy proxy = buildMeshProxy(mesh, map, heightScale);
//           // draw proxy.positions (3 a triangle) with proxy.meshTriangles as a flat
//           // attribute; the shader traces prism meshTriangles[k] over t in
//           // [0, proxy.topHeights[meshTriangles[k]]]
//
// Per mesh triangle (vertices P_i, unit normals N_i, texture coordinates T_i, s the height
// scale):
//
//  * H_tri, its top height (topHeight()): the largest sample the triangle's heights can
//    read, h(uv(b)) <= H_tri over the whole triangle, for bilinear and biquadratic
//    interpolation alike (the argument is at topHeight() in src/core/base/MeshProxy.cpp).
//  * Its hull: the convex hull of the six corners P_i and P_i + s H_tri N_i. The prism
//    { X(b, t) = B(b) + s t D(b) : b in the triangle, 0 <= t <= H_tri } lies in it, as
//    X(b, t) = sum_i b_i (1 - t / H_tri) P_i + b_i (t / H_tri) (P_i + s H_tri N_i) is a
//    convex combination of the six (weights >= 0, summing to 1), whatever the normals do:
//    twisted side walls, prisms that fold over themselves (a shell thicker than the
//    mesh's curvature radius), top corners that meet at a focal point. So a ray that
//    meets the prism's solid at ray parameter lambda either starts inside the hull or
//    crosses its boundary at some parameter <= lambda: drawn without face culling, the
//    hull gives that ray a fragment of this prism (a back face for an eye inside it, so
//    the shader traces from max(entry, 0)).
//
// Why the hull, and not bottom + top + both diagonal splits of each bilinear side wall (14
// triangles): the hull holds every point of the prism by the convex combination above,
// folds included, where the 14 triangles enclose only the images of the prism's faces
// (a fold's envelope can stand outside them), and it costs at most 8 triangles (a convex
// polyhedron of 6 vertices has at most 2 * 6 - 4 faces): 8 for a prism in general
// position, 2 for a flat one. Degenerate cases: H_tri = 0 (the map is 0 over the
// triangle; the prism is the triangle itself), or a hull thinner than its padding: the
// triangle drawn twice, once in each winding, so that either face culling keeps one; top
// corners that meet (a focal point) or coplanar corners (a flat quad side): the hull of
// the distinct points, each planar face one fan.
//
// Conservative in float: the hull is computed in double, then each vertex is moved out by
// at least `padding` across every hull face that holds it, before it is rounded to float:
// every point of every face then moves outward of that face's plane by at least padding
// less the rounding (half an ulp a coordinate), so the float surface still encloses the
// exact hull. padding: 32 2^-24 of the largest coordinate of the mesh's shell (16 float
// ulps there or more; 2e-6 of that coordinate); where a hull comes to a sharp edge (a
// knife-like fold), the vertex moves further, as it must.
//
// Each proxy triangle is wound counter-clockwise seen from outside its hull and carries
// its mesh triangle's index. Cost: at most 8 proxy triangles (24 float3 positions and 8
// indices) a mesh triangle; a pixel is shaded once for each hull its ray crosses, twice
// without culling (a front and a back face). The eye inside a hull (inside the shell, or
// near a fold) sees only that hull's back faces: drawn with back faces culled, such a hull
// gives no fragment, so either everything is drawn without culling, or the hulls that hold
// the eye (hullsThatMayHold(), per frame) are drawn without it and the rest with back
// faces culled. Building it takes about 7 microseconds a triangle for the hull and
// a read of each sample in H_tri's texels (Debian's assimp-testmodels spider.obj, 1312
// triangles whose uv boxes hold 8457 samples of a 512 x 512 map on average: 24 ms, one core,
// 2026-12-07).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

struct MeshProxy {
    // Three positions a proxy triangle, in the mesh's units, counter-clockwise seen from
    // outside its hull; a mesh triangle's proxy triangles are consecutive.
    std::vector<glm::vec3> positions;
    // Per proxy triangle: the index of the mesh triangle (TriangleMesh::triangles) whose
    // prism's hull it bounds.
    std::vector<std::uint32_t> meshTriangles;
    // Per mesh triangle: its proxy triangles are [firstProxyTriangle[k],
    // firstProxyTriangle[k + 1]); one more entry than the mesh has triangles.
    std::vector<std::uint32_t> firstProxyTriangle;
    // Per mesh triangle: H_tri, the top height in the map's units (t, not s t): h(uv(b))
    // <= H_tri over the whole triangle.
    std::vector<float> topHeights;
    // The outward margin of every hull face, in the mesh's units (see the header).
    double padding = 0.0;

    std::size_t triangleCount() const { return meshTriangles.size(); }
};

// H_tri of a triangle whose texture coordinates are `t0`, `t1`, `t2`: the largest sample
// of the map (repeated in u and v) in the texels the triangle's uv bounding box touches and
// one texel around them; the map's largest sample where that box spans the whole map in
// both directions or more than 65536 samples.
float topHeight(const HeightMap& map, glm::dvec2 t0, glm::dvec2 t1, glm::dvec2 t2);

// The proxy of `mesh` (normals unit length, triangles of non-zero area: what
// io/MeshFile.h's loadMeshFile gives) under `map` (non-empty, heights finite and >= 0) at
// height scale `heightScale` (s, in the mesh's units, >= 0). The interpolation does not
// matter: H_tri bounds both.
MeshProxy buildMeshProxy(const TriangleMesh& mesh, const HeightMap& map, double heightScale);

// The mesh triangles whose proxy may enclose `point` (an eye): those whose proxy's float
// vertices' box holds it, a superset of those whose hull holds it (a closed surface
// encloses nothing outside its vertices' convex hull, which the box holds; and the float
// surface encloses the exact hull). Drawn without face culling, they give an eye inside
// them their back faces' fragments; the others can be drawn with back faces culled. In
// increasing order; O(triangles).
std::vector<std::uint32_t> hullsThatMayHold(const MeshProxy& proxy, const glm::dvec3& point);

}  // namespace microrelief
