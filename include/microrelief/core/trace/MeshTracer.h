// The mesh base's traversal on the CPU (docs/bases.md, "The mesh's traversal"; issue 50):
// the multilevel method of the paper run in one triangle's prism at a time, in that prism's
// map space, as the mesh's fragment shader is to run it (one rasterised prism, one fragment,
// one trace; the depth test keeps the least over prisms). trace() takes the least over all
// prisms whose box the ray crosses, as the depth test would.
//
// use:      MeshTracer tracer(mesh, map, heightScale, interpolation);
//           MeshTraceHit hit = tracer.trace(ray);          // ray in the mesh's units
//           MeshTraceHit one = tracer.traceTriangle(ray, k, lambdaMax, stats);  // one prism
//
// Per (ray, triangle) the ray's preimage in the prism X(b, t) = B(b) + s t D(b) is a curve
// parametrised by the height t itself (MeshReference.h has the algebra):
//   lambda(t) = num(t) / c(t), b_k(t) = n_k(t) / c(t), uv(t) = sum b_k(t) T_k,
// c quadratic, num cubic, n_k quadratic (a PrismPath holds them). [0, H] (H the pyramid's
// top) is cut at the roots of c (poles), of n_k (the curve leaves the triangle: walls), and of
// the numerators of the derivatives of lambda (folds; degree 4), b_k, u and v (degree 2: the
// cubic terms of n' c - n c' cancel). On each piece (a MeshPiece) lambda, t, b and uv are
// monotone, b has one sign pattern (pieces outside the triangle are dropped), and lambda is
// clipped to [0, lambdaMax] (the triangle's box exit or the best hit so far) by bisection on
// the sign of num - L c. A ray parallel to every offset plane (c = 0 identically: level over
// a flat mesh, along a tube's axis) lies in the offset planes at the roots of num: level
// pieces, parametrised by lambda, t fixed, b linear in lambda.
//
// The traversal walks a piece's parameter p in [0, 1] (p = 0 its lower-lambda end; t linear in
// p on a curve piece, lambda linear on a level piece) with the very walk MultilevelTracer runs
// over a segment of a ray (core/trace/SegmentWalk.h, segment_walk.glsl: binary subdivision, near
// half first, one pyramid read per segment, the parent's bound, the far half's climb): the
// piece is the walk's path (MeshTracer::PiecePath), answering the base-seam questions
// (BaseSurface.h) for the piece:
//  * lowest: the lesser of t at the segment's two ends. Exact: t is linear in p (a constant on
//    a level piece), so its least over [pa, pb] is at an end;
//  * footprint: the box of uv at the two ends, in texels, widened by 1e-9 texel plus 1e-12 of
//    the coordinate (double rounding of n / c, far below that). A bound: u and v are
//    monotone on the piece, so every point of the segment's path lies between its ends';
//  * descendTo(h): where t comes down to h, t being linear in p (pa when it starts there).
// A footprint is read through the pyramid of the map repeated in u and v (the contract's
// addressing): per axis taken into one period, split in two where it crosses the period's
// edge, the whole axis where it spans a period; the finest texels bound their squares with the
// wrapped neighbours (a 3 x 3 tiled pyramid, MaxPyramid.h's finestBound over the first and the
// last tile). The leaf walks the cells the segment's path crosses in order (u and v monotone:
// each cell's exit where u or v crosses its boundary, found by bisection on the monotone
// coordinate), and in each cell solves patch(uv(p)) - t(p) >= 0 as MultilevelTracer's
// cellStretchHit does: subdivided near half first, a piece dropped when its lowest t is above
// the patch's max over its uv box (exact for bilinear patches, the Bezier net's for
// biquadratic ones), final pieces (2^-12 texel and 2^-12 of H, or 2^-40 of the stretch) solved
// by the parabola through their ends and middle. No bound is ever below the surface, so no
// contact is dropped; a hit is never after the true one by more than a final piece.
//
// Where the hit is: Top (inside a piece, t = h), or where a piece starts already at or below
// the surface: Base (t = 0, the mesh itself), Wall (b_k = 0), Fold (lambda turns), Inside
// (lambda = 0, the ray's origin in the solid). A wall b_k = 0 on a smooth edge
// (smoothEdges) is no surface: a piece that starts on it is on the top or the mesh there.
//
// Not handled apart (the reference does it): a curve piece's end at a common root of num and
// c (a ray lying in one offset plane of a curved triangle, a focal height); such an end is
// taken as computed. Float: the parameter is t, so in float a ray at a grazing angle g to the
// mesh resolves a texel of size e only while g e is well above H 2^-24 (the GLSL's limit to
// state); in double here, for g down to about 1e-13 H / e.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/trace/MeshReference.h"

namespace microrelief {

// Per triangle, bit i set where the wall b_i = 0 is no surface of the solid (the contract: walls
// stand only where the neighbouring prisms' heights differ): the edge opposite vertex i is
// shared by exactly two triangles (no other triangle has an edge with those two positions),
// run the other way round in the other, with the same positions and normals at both ends
// (float equality), and texture coordinates that differ there by one vector of integers (the
// map repeats). Then the two prisms' walls on that edge are the same ruled surface, the heights
// along it the same function, and the solids meet there with nothing exposed between them.
// A UV seam, a hard edge (normals split), the mesh's border and an edge of three triangles
// keep their walls.
std::vector<std::uint8_t> smoothEdges(const TriangleMesh& mesh);

// A polynomial in t, coefficients of t^0 .. t^4.
using MeshPolynomial = std::array<double, 5>;

// One ray in one triangle's prism: what a piece needs to map its parameter to (lambda, t, b,
// uv). Built once per (ray, triangle), as the fragment builds it from the prism's flat inputs.
struct PrismPath {
    MeshPolynomial c{}, num{}, n1{}, n2{};  // lambda = num / c, b_1 = n1 / c, b_2 = n2 / c
    glm::dvec2 uv0{0.0}, uv1{0.0}, uv2{0.0};  // the corners' texture coordinates
    bool level = false;                       // c = 0 identically: level pieces only
    glm::dvec3 levelB0{0.0}, levelB1{0.0};    // per level piece root: b = B0 + lambda B1
};

// A stretch of the ray's preimage on which lambda, t, b and uv are monotone and b lies in the
// triangle; p in [0, 1] runs from its lower-lambda end (A) to its other end (B).
struct MeshPiece {
    bool level = false;     // t fixed at tA, lambda linear in p (else t linear in p)
    double tA = 0.0, tB = 0.0;
    double lambdaA = 0.0, lambdaB = 0.0;
    glm::dvec3 levelB0{0.0}, levelB1{0.0};  // level: b = B0 + lambda B1
    MeshSurface entry = MeshSurface::Top;   // what starting at A below the surface means
    int wall = -1;                          // entry Wall: which, b_wall = 0
};

// The path's point at a piece's parameter.
struct MeshPathPoint {
    double lambda = 0.0, t = 0.0;
    glm::dvec3 b{0.0};
    glm::dvec2 uv{0.0};
};

struct MeshTraceStats {
    int triangles = 0;   // prisms traced (their boxes crossed)
    int pieces = 0;      // pieces walked
    int iterations = 0;  // segments visited, all pieces
    int fetches = 0;     // pyramid texels and patches read, counted as MultilevelTracer does
    bool exhausted = false;
};

struct MeshTraceHit {
    MeshSurface surface = MeshSurface::None;
    double t = 0.0;  // ray parameter
    glm::dvec3 position{0.0};
    std::size_t triangle = 0;
    glm::dvec3 barycentric{0.0};
    double height = 0.0;  // the contract's t
    glm::dvec2 uv{0.0};   // not wrapped
    explicit operator bool() const { return surface != MeshSurface::None; }
};

class MeshTracer {
public:
    // As MeshReference: the contract's mesh, map (finite, >= 0) and s; copied.
    MeshTracer(const TriangleMesh& mesh, HeightMap map, double heightScale,
               Interpolation interpolation = Interpolation::Bilinear);

    // The first hit over all prisms.
    MeshTraceHit trace(const Ray& ray, MeshTraceStats* stats = nullptr) const;
    // The first hit in triangle `k`'s prism with ray parameter in [0, lambdaMax]: one
    // fragment's work (stats added to).
    MeshTraceHit traceTriangle(const Ray& ray, std::size_t k, double lambdaMax,
                               MeshTraceStats& stats) const;

    // The pieces of `ray` in triangle k's prism with lambda in [0, lambdaMax], ordered by
    // lambdaA; `path` is set for pointOn.
    static constexpr int kMaxPieces = 32;
    int pieces(const Ray& ray, std::size_t k, double lambdaMax, PrismPath& path,
               std::array<MeshPiece, kMaxPieces>& out) const;
    MeshPathPoint pointOn(const PrismPath& path, const MeshPiece& piece, double p) const;
    // The ray parameter range of triangle k's box (empty: x > y).
    glm::dvec2 boxSpan(const Ray& ray, std::size_t k) const;

    // The pyramid's bound over the texel rectangle [lo, hi] (X = u W, Y = v H, any values: the
    // map repeats), never below the repeated surface there; fetches as the walk counts them.
    BoundRead footprintBound(glm::dvec2 lo, glm::dvec2 hi) const;

    const MaxPyramid& pyramid() const { return pyramid_; }
    double top() const { return top_; }
    std::size_t triangleCount() const { return triangles_.size(); }

private:
    struct Triangle {
        glm::dvec3 p0, e1, e2, n0, f1, f2;  // P0, P1 - P0, P2 - P0, N0, N1 - N0, N2 - N0
        glm::dvec2 uv0, uv1, uv2;
        glm::dvec3 boxLo, boxHi;
        std::uint8_t smooth = 0;  // smoothEdges' bits
    };
    PrismPath path(const Ray& ray, const Triangle& tri) const;
    glm::dvec3 texelPoint(const MeshPathPoint& m) const;  // (X, Y, t)
    double surfaceAt(glm::dvec2 uv, MeshTraceStats& stats) const;
    // A piece as the path of the shared segment walk (core/trace/SegmentWalk.h).
    class PiecePath;
    double leaf(const PrismPath& path, const MeshPiece& piece, double p0, double p1,
                MeshTraceStats& stats) const;

    std::vector<Triangle> triangles_;
    HeightMap map_;
    Interpolation interpolation_;
    MapAddressing repeat_;  // 3 x 3 tiles: every cell's samples from the middle tile
    MaxPyramid pyramid_;
    double heightScale_, top_;
    int maxIterations_;
};

}  // namespace microrelief
