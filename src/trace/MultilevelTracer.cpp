#include "trace/MultilevelTracer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace microrelief {

namespace {

constexpr int kMaxDepth = 24;         // MICRORELIEF_MAX_DEPTH
constexpr double kLeafTexels = 4.0;  // MICRORELIEF_LEAF_TEXELS

using Cell = MultilevelTracer::Cell;

// Fetches are counted as the shader's GLSL 4.00 variant counts them: one textureGather
// per patch (bilinear_patch.glsl), one texel per pyramid read.
Cell cellAt(const HeightMap& map, double x, double y, int& fetches) {
    const int i = static_cast<int>(std::floor(x - 0.5)), j = static_cast<int>(std::floor(y - 0.5));
    fetches += 1;
    return {i,
            j,
            map.clamped(i, j),
            map.clamped(i + 1, j),
            map.clamped(i, j + 1),
            map.clamped(i + 1, j + 1)};
}

// bilinear_patch.glsl: intersectPatch.
double intersectPatch(const Cell& c, const glm::dvec3& start, const glm::dvec3& dir,
                      double tauMax) {
    const double fx = start.x - (c.i + 0.5), fy = start.y - (c.j + 0.5);
    const double b = c.h10 - c.h00, cc = c.h01 - c.h00, d = c.h00 - c.h10 - c.h01 + c.h11;
    // g(tau) = patch height - ray height: the hit is the first tau with g >= 0.
    const double C = c.h00 + b * fx + cc * fy + d * fx * fy - start.z;
    if (C >= 0.0) return 0.0;
    const double B = b * dir.x + cc * dir.y + d * (fx * dir.y + fy * dir.x) - dir.z;
    const double A = d * dir.x * dir.y;
    double root = -1.0;
    if (std::abs(A) * tauMax <= 1e-12 * std::abs(B)) {
        if (B > 0.0) root = -C / B;
    } else {
        const double disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            const double q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * std::sqrt(disc));
            const double r1 = q / A, r2 = q != 0.0 ? C / q : -1.0;
            const double lo = std::min(r1, r2), hi = std::max(r1, r2);
            root = lo >= 0.0 ? lo : hi;
        }
    }
    return (root >= 0.0 && root <= tauMax) ? root : -1.0;
}

}  // namespace

int traversalBudget(int width, int height) {
    return 8 * (width + height) + 256;
}

MultilevelTracer::MultilevelTracer(HeightMap map, double heightScale)
    : map_(std::move(map)),
      pyramid_(map_),
      heightScale_(heightScale),
      maxIterations_(traversalBudget(map_.width, map_.height)) {}

// multilevel_trace.glsl: setTopHit's normal, in world space.
glm::dvec3 MultilevelTracer::topNormal(const Cell& cell, const glm::dvec3& mapPoint) const {
    const double fx = std::clamp(mapPoint.x - (cell.i + 0.5), 0.0, 1.0);
    const double fy = std::clamp(mapPoint.y - (cell.j + 0.5), 0.0, 1.0);
    double gx = (cell.h10 - cell.h00) * (1 - fy) + (cell.h11 - cell.h01) * fy;
    double gy = (cell.h01 - cell.h00) * (1 - fx) + (cell.h11 - cell.h10) * fx;
    // Clamped border cells are flat across the edge.
    if (cell.i < 0 || cell.i >= map_.width - 1) gx = 0.0;
    if (cell.j < 0 || cell.j >= map_.height - 1) gy = 0.0;
    const double slope = heightScale_ * std::max(map_.width, map_.height);
    return glm::normalize(glm::dvec3(-slope * gx, 1.0, -slope * gy));
}

// multilevel_trace.glsl: intersectLeaf. The cells the segment crosses, in ray order, each
// solved exactly; from a cell to the neighbour across the boundary the ray meets first.
auto MultilevelTracer::intersectLeaf(const MapRay& ray, double ta, double tb, int& fetches) const
    -> std::optional<LeafHit> {
    const glm::dvec3 pa = ray.origin + ta * ray.dir, pb = ray.origin + tb * ray.dir;
    glm::ivec2 at(std::floor(pa.x - 0.5), std::floor(pa.y - 0.5));  // the cell's origin sample
    const glm::ivec2 last(std::floor(pb.x - 0.5), std::floor(pb.y - 0.5));
    const glm::ivec2 toward(last.x > at.x ? 1 : last.x < at.x ? -1 : 0,
                            last.y > at.y ? 1 : last.y < at.y ? -1 : 0);
    const int pieces = std::abs(last.x - at.x) + std::abs(last.y - at.y) + 1;
    Cell cell = cellAt(map_, at.x + 1.0, at.y + 1.0, fetches);
    double t0 = ta;
    for (int piece = 0; piece < pieces; ++piece) {
        double exits[2] = {tb, tb};
        for (int axis = 0; axis < 2; ++axis) {
            if (at[axis] != last[axis] && ray.dir[axis] != 0.0) {
                const double boundary = at[axis] + std::max(toward[axis], 0) + 0.5;
                exits[axis] = std::clamp((boundary - ray.origin[axis]) / ray.dir[axis], t0, tb);
            }
        }
        const double t1 = std::min(exits[0], exits[1]);
        const double tau = intersectPatch(cell, ray.origin + t0 * ray.dir, ray.dir, t1 - t0);
        if (tau >= 0.0)
            return LeafHit{t0 + tau, topNormal(cell, ray.origin + (t0 + tau) * ray.dir)};
        if (t1 >= tb) break;
        const int axis = exits[0] <= exits[1] ? 0 : 1;
        at[axis] += toward[axis];
        cell = cellAt(map_, at.x + 1.0, at.y + 1.0, fetches);
        t0 = t1;
    }
    return std::nullopt;
}

std::optional<ReliefHit> MultilevelTracer::intersect(const Ray& worldRay,
                                                     TraversalStats* statsOut) const {
    TraversalStats stats;
    const double texelsPerUnit = std::max(map_.width, map_.height);
    const glm::dvec2 size(map_.width, map_.height);
    const MapRay ray{
        {worldRay.origin.x * texelsPerUnit + 0.5 * size.x,
         worldRay.origin.z * texelsPerUnit + 0.5 * size.y, worldRay.origin.y / heightScale_},
        {worldRay.direction.x * texelsPerUnit, worldRay.direction.z * texelsPerUnit,
         worldRay.direction.y / heightScale_}};
    const double maxHeight = pyramid_.texel(pyramid_.levelCount() - 1, 0, 0);
    auto finish = [&](std::optional<ReliefHit> hit) {
        if (statsOut) *statsOut = stats;
        return hit;
    };
    auto makeHit = [&](HitFace face, double t, glm::dvec3 normal) {
        ReliefHit hit;
        hit.face = face;
        hit.t = t;
        hit.position = worldRay.origin + t * worldRay.direction;
        hit.normal = normal;
        const glm::dvec3 m = ray.origin + t * ray.dir;
        hit.uv = {m.x / size.x, m.y / size.y};
        return hit;
    };

    // multilevel_trace.glsl: clipToReliefBox.
    const glm::dvec3 lo(0.0), hi(size.x, size.y, maxHeight);
    double tEnter = -1e300, tExit = 1e300;
    int entryAxis = -1, exitAxis = -1;
    for (int axis = 0; axis < 3; ++axis) {
        if (ray.dir[axis] == 0.0) {
            if (ray.origin[axis] < lo[axis] || ray.origin[axis] > hi[axis])
                return finish(std::nullopt);
            continue;
        }
        double t0 = (lo[axis] - ray.origin[axis]) / ray.dir[axis],
               t1 = (hi[axis] - ray.origin[axis]) / ray.dir[axis];
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > tEnter) {
            tEnter = t0;
            entryAxis = axis;
        }
        if (t1 < tExit) {
            tExit = t1;
            exitAxis = axis;
        }
    }
    const double tNear = std::max(tEnter, 0.0), tFar = tExit;
    if (tNear > tFar) return finish(std::nullopt);

    const glm::dvec3 entry = ray.origin + tNear * ray.dir;
    const bool throughTop = entryAxis == 2 && ray.dir.z < 0.0;
    const bool throughBottom = entryAxis == 2 && ray.dir.z > 0.0;  // h = 0: always in the solid
    if (tEnter >= 0.0 && entryAxis >= 0 && !throughTop &&
        (throughBottom || (stats.fetches += 1, entry.z <= map_.surface(entry.x, entry.y)))) {
        stats.stopLevel = 0;
        glm::dvec3 normal(0.0);
        const double outward = ray.dir[entryAxis] > 0.0 ? -1.0 : 1.0;
        const HitFace face = entryAxis == 0   ? HitFace::WallX
                             : entryAxis == 1 ? HitFace::WallZ
                                              : HitFace::Bottom;
        if (entryAxis == 0) normal.x = outward;
        if (entryAxis == 1) normal.z = outward;
        if (entryAxis == 2) normal.y = outward;
        return finish(makeHit(face, tNear, normal));
    }

    // From the box entry on, as the shader works (relief_hit.glsl: enterReliefBox).
    const MapRay fromEntry{ray.origin + tNear * ray.dir, ray.dir};
    if (auto hit = subdivideSegment(fromEntry, tFar - tNear, exitAxis, stats)) {
        return finish(makeHit(HitFace::Top, tNear + hit->t, hit->normal));
    }
    return finish(std::nullopt);
}

// multilevel_trace.glsl: subdivideSegment, over ray.origin + t ray.dir, t in [0, span].
// The shader splits this loop in two (segments inside, the leaf outside) for the sake of
// SIMD lanes; the segments and their order are the same, and a GL test compares them
// per pixel.
auto MultilevelTracer::subdivideSegment(const MapRay& ray, double span, int exitAxis,
                                        TraversalStats& stats) const -> std::optional<LeafHit> {
    const double unit = std::ldexp(1.0, -kMaxDepth);
    constexpr double kNoBound = std::numeric_limits<double>::infinity();
    int depth = 0;
    std::uint32_t index = 0;
    double parentBound = kNoBound;  // over the parent's path (see the shader)
    const bool floorExit = exitAxis == 2 && ray.dir.z < 0.0;
    for (int iteration = 1; iteration <= maxIterations_; ++iteration) {
        stats.iterations = iteration;
        const int shift = kMaxDepth - depth;
        const double ta = span * (static_cast<double>(index << shift) * unit);
        const double tb = span * (static_cast<double>((index + 1u) << shift) * unit);
        const glm::dvec3 pa = ray.origin + ta * ray.dir, pb = ray.origin + tb * ray.dir;
        const glm::dvec2 extents = glm::abs(glm::dvec2(pb) - glm::dvec2(pa));
        const double extent = std::max(extents.x, extents.y);
        // Down to the floor (ending where the ray leaves through it): may hit; above the
        // parent's bound: cannot; else one window.
        const double lowest = std::min(pa.z, pb.z);
        bool mayHit = floorExit && tb == span;
        double bound = parentBound;
        if (!mayHit && lowest <= parentBound) {
            int level = 0;
            bound = std::min(bound, pyramid_.segmentBound(pa, pb, level, stats.fetches));
            stats.stopLevel = level;
            mayHit = lowest <= bound;
        }
        if (mayHit) {
            if (extent <= kLeafTexels || depth >= kMaxDepth) {
                // From where a falling ray comes down to the bound (see the shader).
                const double tFrom =
                    ray.dir.z < 0.0 ? std::clamp((bound - ray.origin.z) / ray.dir.z, ta, tb) : ta;
                if (auto hit = intersectLeaf(ray, tFrom, tb, stats.fetches)) return hit;
            } else {
                // The near half, or the far one when the near one lies above the bound.
                ++depth;
                index *= 2u;
                parentBound = bound;
                const double middleZ = ray.origin.z + 0.5 * (ta + tb) * ray.dir.z;
                if (std::min(pa.z, middleZ) > bound) ++index;
                continue;
            }
        }
        // On to index + 1 at this depth; after a far half cleared by a wide margin, one
        // level up (see the shader).
        const bool farHalf = (index & 1u) == 1u;
        ++index;
        if ((index >> depth) != 0u) {
            // Leaving through the floor going down: the exit point is the hit (see the shader).
            if (exitAxis == 2 && ray.dir.z < 0.0) {
                const glm::dvec3 exit = ray.origin + span * ray.dir;
                return LeafHit{span, topNormal(cellAt(map_, exit.x, exit.y, stats.fetches), exit)};
            }
            return std::nullopt;
        }
        if (farHalf) {
            parentBound = kNoBound;
            if (lowest - bound > 2.0 * std::abs(pb.z - pa.z)) {
                index >>= 1;
                --depth;
            }
        }
    }
    stats.exhausted = true;
    return std::nullopt;
}

}  // namespace microrelief
