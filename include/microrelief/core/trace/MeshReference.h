// The exact reference for relief on a triangle mesh (docs/bases.md, "The mesh"; issue 50),
// in double precision, written from the contract's text alone: it shares nothing with a
// shader, the traversal or the other references (its own height function, its own root
// search). The ground truth the mesh's renderer and its CPU twin are to be held to.
//
// use:      MeshReference reference(mesh, map, heightScale, interpolation);
//           MeshHit hit = reference.trace(ray);   // ray in the mesh's units
// options:  Interpolation::Bilinear or Biquadratic, the map repeated in u and in v.
//
// The solid (the contract): per triangle with vertices P_i, unit normals N_i, texture
// coordinates T_i and barycentrics b, X(b, t) = B(b) + s t D(b) with B = sum b_i P_i,
// D = sum b_i N_i (linear, not renormalised), uv(b) = sum b_i T_i; the triangle's prism is
// { X(b, t) : b in the closed triangle, 0 <= t <= h(uv(b)) }, the relief the union of the
// prisms. A hit is the first point of the ray (ray parameter >= 0) in that closed solid.
//
// How it is solved (the design; src/core/trace/MeshReference.cpp has the details):
//
//  * For a fixed t the offset triangle { X(b, t) } is planar: its corners P_i + s t N_i.
//    A point Y lies on the offset plane of height t where det(Y - Q(t), A1(t), A2(t)) = 0,
//    Q(t) = P_0 + s t N_0, A_k(t) = P_k - P_0 + s t (N_k - N_0): a cubic in t, so a point
//    of space has up to three preimages (b, t) in one triangle's extended prism, which is
//    how prisms fold (a shell thicker than the mesh's curvature radius).
//  * Along the ray Y(lambda) = O + lambda V that condition is num(t) - lambda c(t) = 0 with
//    c(t) = det(A1, A2, V) (quadratic) and num(t) cubic: the ray's preimage is the curve
//    lambda = num(t) / c(t), one lambda for each t, and b(t) = n(t) / c(t) with quadratic
//    numerators. In the map the ray's path (uv(lambda), t(lambda)) is curved, and the
//    triangle's first hit is the least lambda on that curve with b in the triangle,
//    0 <= t <= h(uv): where t(lambda) = h(uv(lambda)) first (the top), or where the ray
//    comes into the prism already below the top, through the bottom face t = 0 (the mesh
//    itself), a side wall b_i = 0 (a ruled, bilinear surface between two vertices' normal
//    lines, not a plane) or a fold (where lambda(t) turns: there two preimages appear at
//    once, inside the prism's domain, on the envelope of its offset triangles). The
//    mesh's hit is the least over triangles.
//  * The t range [0, H] (H >= h over the triangle) is cut at every t where c vanishes or
//    turns, where lambda(t) turns (the folds, num' c - num c' = 0) and where b_0, b_1,
//    b_2, u or v turns (n' c - n c' = 0, a quadratic each): the real roots of polynomials
//    of degree <= 4, each isolated between the roots of its derivative and bisected to the
//    last bit. On each piece of the curve lambda, t, b and uv are then monotone, so over
//    any stretch of it each lies between its values at the stretch's two ends: bounds,
//    never samples. lambda is clipped to the part of the ray in the triangle's box.
//  * On each piece, in lambda order, the stretch is bisected, near half first (lambda as
//    the parameter: t(lambda) is the root of num - lambda c in the piece's t bracket, b the
//    projection of Y - Q(t) on the offset plane, both well conditioned however grazing
//    the ray). A stretch is discarded only when every point of it is outside the solid:
//    some b_i below 0 at both ends, or its lowest t above the largest h over the
//    rectangle its uv span (exact for bilinear patches, which peak at a corner of any
//    axis-parallel rectangle in a cell; the Bezier net's largest point, which no
//    biquadratic patch exceeds, for biquadratic ones). No point of the solid is ever
//    discarded, so the first stretch left at width `tolerance()` holds the first hit.
//  * Where num and c share a root tc the factor t - tc is divided out of both, so that
//    each bracket holds one root for each lambda: either the ray lies in the offset plane
//    of height tc (c = 0 identically when it is parallel to all of them: level over a
//    flat mesh, or along the axis of a tube), whose second kind of preimage, all of the
//    ray at t = tc with b linear in lambda, is searched the same way with t fixed; or tc
//    is a focal height, where the offset triangle collapses to a segment or a point
//    (m = A1 x A2 = 0: an inward tube's normal lines all cross its axis), and a piece's
//    end there, where b is undefined, is moved off it by a hair.
//  * Each triangle is culled by the ray against the box of its six corners P_i and
//    P_i + s H N_i: X(b, t) is a convex combination of them, so the prism lies in their
//    hull. Triangles are taken in the order the ray enters their boxes and the search
//    stops once a box starts past the best hit.
//
// Accuracy guaranteed (in exact arithmetic; what float64 adds below): no point of the ray
// before the reported hit lies in the solid, and the stretch [hit, hit + tolerance()]
// could not be excluded by the bounds above, which tighten to the exact values as a
// stretch shrinks: a ray that crosses the solid's boundary at an angle is reported at
// most a few tolerance() before where it does, tolerance() = 1e-12 of the diagonal of the
// mesh's shell (a length: the ray parameter's tolerance is that over |V|). A ray that
// comes within about tolerance() of the solid without entering it may be reported as
// touching it, as the closed solid has it. Float64 rounding: t, b and uv come from solves
// whose error is a few ulps of the triangle's size, except at a fold, where t is fixed
// only to the square root of that (the position stays accurate); a hit on a surface the
// ray meets at a grazing angle g moves along the ray by that error over g, as on every
// reference. Measured (tests/cpu/MeshReferenceTest.cpp): on a flat grid the plane's
// reference's hits to 5.4e-12 of a unit scene, level, grazing and border rays included.
// The normal (MeshHit::normal) is the surface's at the reported point, in closed form: to
// 1.5e-10 the plane's normals on a flat grid, to 1e-9 the central differences of the top
// on tubes and folded meshes; at a fold it follows t, found there to about the square
// root of the tolerance (its side is tested, its direction only by the formula). On an
// edge of the solid (where the top meets a wall, or two walls meet) it is the normal of
// the surface the hit is classed on.
//
// Cost: a ray takes about 10 microseconds over a 320-triangle sphere of cobbles (a 64 x 64
// picture 0.05 s, 256 x 256 0.8 s, one core). A test reference, not a renderer.
#pragma once

#include <cstddef>
#include <memory>

#include <glm/glm.hpp>

#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Camera.h"

namespace microrelief {

// Where the ray meets the solid. Top: t = h(uv), the relief. Base: t = 0, the mesh itself
// (a ray from below or from behind the mesh). Wall: b_i = 0, a side wall of a prism that
// no neighbour's solid covers: the mesh's border, or a UV seam where the heights on the two
// sides differ. Fold: where a prism folds over itself (a shell thicker than the mesh's
// curvature radius), on the envelope of its offset triangles, none of the above holding
// with equality there. Inside: the ray's origin is in the solid (hit at ray parameter 0).
enum class MeshSurface { None, Top, Base, Wall, Fold, Inside };

struct MeshHit {
    MeshSurface surface = MeshSurface::None;
    double t = 0.0;               // ray parameter, in units of the ray direction's length
    glm::dvec3 position{0.0};     // origin + t direction, the mesh's units
    std::size_t triangle = 0;     // index into TriangleMesh::triangles
    glm::dvec3 barycentric{0.0};  // b of the triangle's three vertices, in index order
    double height = 0.0;          // the contract's t: 0 <= height <= h(uv)
    glm::dvec2 uv{0.0};           // sum b_i T_i, not wrapped into [0, 1)
    // The outward unit normal of the surface hit, in the mesh's frame (the gradient of the
    // function whose level set the surface is, pointing out of the solid): Top, the normal
    // of X(b, h(uv(b))), dX/db_1 x dX/db_2 with dX/db_k = E_k + s h F_k + s (dh/db_k) D;
    // Base, the mesh triangle's own normal away from D; Wall, the normal of the ruled
    // surface between the two vertices' normal lines, away from the triangle; Fold, the
    // envelope's normal, facing the ray (the envelope's tangent plane is the range of the
    // singular Jacobian; the side is the ray's, which enters there). Zero for Inside.
    glm::dvec3 normal{0.0};
    explicit operator bool() const { return surface != MeshSurface::None; }
};

class MeshReference {
public:
    // `heightScale` is the contract's s, in the mesh's units; the map must be non-empty
    // with finite heights >= 0, the mesh's normals unit length and its triangles of
    // non-zero area (what io/MeshFile.h's loadMeshFile gives). Both are copied from.
    MeshReference(const TriangleMesh& mesh, const HeightMap& map, double heightScale,
                  Interpolation interpolation = Interpolation::Bilinear);
    ~MeshReference();
    MeshReference(MeshReference&&) noexcept;
    MeshReference& operator=(MeshReference&&) noexcept;

    // The first point of `ray` (parameter >= 0; the direction need not be unit length)
    // in the closed solid, or surface None.
    MeshHit trace(const Ray& ray) const;

    // The length to which a hit is found (see the header's accuracy).
    double tolerance() const;

private:
    struct Data;
    std::unique_ptr<Data> data_;
};

}  // namespace microrelief
