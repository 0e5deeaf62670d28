// The exact CPU reference tracer: the ground truth the GPU renderer is checked against.
// It shares no code with the multilevel tracer on purpose. On the plane it walks the
// bilinear cells the ray crosses (a 2D DDA) and solves the ray against each cell's
// bilinear patch exactly (a quadratic in t), in double precision, against the solid of the
// spec (scene-and-cli.md, "Height map to surface"): the top surface, the side walls and
// the bottom face. On a curved base (core/trace/CurvedReference.cpp) the path of the ray over
// the map is a curve and the surface along it no longer a polynomial: it lists every
// crossing of a cell boundary in closed form, and in each cell finds the first contact by
// bisection with a Lipschitz bound of the gap, to 1e-12 of the ray's length. The cost is
// O(cells crossed) per ray.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/PyramidPages.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/ModelTransform.h"

namespace microrelief {

// The face of the solid a ray hits. WallX: the walls x = +-a/2; WallZ: z = +-b/2 (the
// plane); Cap: an end of the cylinder. Top is the relief surface on every base.
enum class HitFace { None, Top, WallX, WallZ, Bottom, Cap };

struct ReferenceHit {
    HitFace face = HitFace::None;
    double t = 0.0;            // ray parameter, in units of the ray direction's length
    glm::dvec3 position{0.0};  // world position of the hit
    glm::dvec3 normal{0.0};    // world unit normal, outward; on top the bilinear surface normal
    glm::dvec2 uv{0.0};        // map uv of the hit (u = X/W, v = Y/H)
    // Hit or not: the face of the relief's bounding box the ray comes in through, WallX,
    // WallZ or Bottom; None for the top face, an origin inside the box, or no box at all.
    HitFace entryFace = HitFace::None;
    explicit operator bool() const { return face != HitFace::None; }
};

// The scene of the spec for one map: on the plane the solid {|x| <= a/2, |z| <= b/2,
// 0 <= y <= s h(u, v)}; on a curved base the column or the star-shaped body of
// core/base/BaseShape.h.
struct ReliefGeometry {
    const HeightMap* map;  // not owned; must be non-empty with heights >= 0
    double heightScale = 0.1;
    BaseShape base = {};
    Interpolation interpolation = Interpolation::Bilinear;
    // Where the relief sits in the world: rays and hits are the world's, the solid above
    // is in object space (core/scene/ModelTransform.h).
    ModelTransform model = {};
};

// The exact first hit of `ray` (world space) with the relief solid: its first point with
// t >= 0 inside the closed solid, or face None. A ray that enters through a side wall
// or the bottom face reports that face; a ray whose origin lies inside the solid hits at
// t = 0 and reports Top there (the spec keeps the eye outside the solid). Not knowing
// the relief's top, it walks every cell under the ray's path across the footprint,
// those high above the relief included: for many rays use ReferenceTracer.
ReferenceHit traceReference(const ReliefGeometry& relief, const Ray& ray);

// traceReference for many rays against one relief: it finds the relief's top once
// (O(W H)) so that each ray walks only the cells below it (a 4096^2 map, 128^2 rays:
// about 100 times faster). The same hits; the map must not change while in use.
namespace detail {
// The cell boundaries of a curved base's map, once per map: the half-planes of constant u
// as (sin, cos) of their angle, the cones (or planes) of constant v as the cosine of their
// polar angle (the cylinder's as their height).
struct CurvedBoundaries {
    std::vector<glm::dvec2> u;
    std::vector<double> v;
};
CurvedBoundaries curvedBoundaries(const ReliefGeometry& relief);
// The curved bases' reference (core/trace/CurvedReference.cpp); `top` is s times the largest
// sample.
ReferenceHit traceCurvedReference(const ReliefGeometry& relief, const CurvedBoundaries& boundaries,
                                  const Ray& ray, double top);
}  // namespace detail

class ReferenceTracer {
public:
    explicit ReferenceTracer(const ReliefGeometry& relief);
    ReferenceHit trace(const Ray& ray) const;

private:
    ReliefGeometry relief_;
    double top_;                           // s times the largest sample
    detail::CurvedBoundaries boundaries_;  // curved bases only
};

// The plane's reference over a map that is not in memory whole: its samples read from
// `pages` (core/heightmap/PyramidPages.h, page level 0: a pyramid file's) a block of
// 256 x 256 at a time as the walk reaches them, the last 32 blocks kept. The same walk as
// ReferenceTracer's on the plane, so the same hits over the same samples, bit for bit; a
// ray costs its cells and the blocks they lie in. For pictures of such maps checked on
// sampled pixels (microrelief-render --pyramid-cache --compare-reference). Not for two
// threads at once.
class PagedReferenceTracer {
public:
    PagedReferenceTracer(std::shared_ptr<const PyramidPages> pages, double heightScale,
                         Interpolation interpolation = Interpolation::Bilinear,
                         const ModelTransform& model = {});
    ~PagedReferenceTracer();
    PagedReferenceTracer(const PagedReferenceTracer&) = delete;
    PagedReferenceTracer& operator=(const PagedReferenceTracer&) = delete;

    ReferenceHit trace(const Ray& ray) const;
    // Blocks of samples read so far (each of up to 256^2 samples).
    std::size_t blocksRead() const;

private:
    class Samples;
    std::unique_ptr<Samples> samples_;
    double heightScale_;
    Interpolation interpolation_;
    ModelTransform model_;
    double top_;  // s times the largest sample
};

}  // namespace microrelief
