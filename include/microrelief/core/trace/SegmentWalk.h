// The one walk over the binary subdivision of a path (Vyatkin & Romaniuk, section III, eq. 8,
// fig. 5-6) that every base's CPU twin runs: MultilevelTracer's frame ray over the plane, a
// cylinder or an ellipsoid, and MeshTracer's pieces in a triangle's prism (docs/bases.md, "The
// mesh's traversal"; issue 50: the base table grows by a row, not by a fork). The walk is the
// mechanics (segments named by depth and index, near half first, one pyramid read a segment
// unless the parent's bound already clears it, the far half's climb, the leaf); a path says
// what a segment of it is on the map.
//
// A path is parametrised by p in [0, span()] (the frame ray: its t from the shell's entry;
// a mesh piece: its p in [0, 1], t linear in p or lambda on a level piece). It answers, for a
// segment [pa, pb] (its own file says why each answer is a bound in its units):
//   Footprint footprint(pa, pb)       texel box lo, hi of the segment's path, its lowest height
//                                     and its drop (BaseSurface.h's Footprint);
//   double lowest(pa, pb)             footprint().lowest alone;
//   double bound(footprint, stats)    the pyramid's bound over the footprint, never below the
//                                     surface there; counts its reads in stats;
//   double descendTo(pa, pb, h)       the first p at which the path is at or below h, never later;
//   std::optional<Hit> leaf(from, to, stats)
//                                     the exact first contact on [from, to], cell by cell;
//   bool floorExit()                  the path ends going down through h = 0 (the plane's box):
//                                     its last segment may hit, and its end is a hit;
//   std::optional<Hit> floorHit(stats)  that end's hit.
// Stats has int iterations (segments visited, added to) and bool exhausted (the budget ran out).
//
// A template, not a virtual interface: a virtual path measured the same (the walk's own steps
// are a small part of a ray's time beside the base's answers and the leaf; docs/bases.md, "The
// mesh's traversal"), and the template costs nothing and is the GLSL's compile-time choice.
//
// The GLSL mirror. Analytic bases (segment_walk.glsl, multilevel_trace.glsl): this loop is
// mr_subdivideSegment, its state mr_SegmentWalk (depth, index, parentBound); path.footprint is
// mr_walkFootprint (the ends placed at span * index 2^-depth, mapped by mr_baseEnd, boxed by
// mr_baseFootprintOf), path.bound mr_walkBound (mr_footprintBound), the leaf test
// mr_walkAtLeaf, path.descendTo mr_baseDescendTo, path.leaf mr_baseIntersectLeaf, the near/far
// choice mr_walkDescend(walk, bound, mr_baseLowest(...) > bound), the step on mr_walkNext with
// the climb, path.floorExit/floorHit mr_finishWalk's floor; the path is chosen per base at
// compile time (each base_*.glsl's mr_base* set), as the template parameter is here. The mesh
// (base_mesh.glsl): mr_meshWalkPiece is this loop over a piece with the same mr_SegmentWalk,
// mr_walkDescend and mr_walkNext; MeshTracer::PiecePath's answers are its lines in place of
// mr_walkFootprint (the ends from mr_meshPointOn, the box of their uv), mr_meshFootprintBound,
// its descend line and mr_meshLeaf. No allocation and a bounded loop (maxIterations), as the
// GLSL needs.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/base/BaseSurface.h"

namespace microrelief {

// multilevel_trace.glsl: mr_subdivideSegment over `path`, at most `maxIterations` segments.
// The shader splits this loop in two (segments inside, the leaf outside) for the sake of SIMD
// lanes; the segments and their order are the same, and a GL test compares them per pixel.
template <class Path, class Stats>
std::optional<typename Path::Hit> walkSegments(const Path& path, int maxIterations,
                                               Stats& stats) {
    const double unit = std::ldexp(1.0, -glsl::kMaxDepth);
    constexpr double kNoBound = std::numeric_limits<double>::infinity();
    const double span = path.span();
    const bool floorExit = path.floorExit();
    int depth = 0;
    std::uint32_t index = 0;
    double parentBound = kNoBound;  // over the parent's path, so over this segment's too
    for (int iteration = 1; iteration <= maxIterations; ++iteration) {
        ++stats.iterations;
        // The ends are integer positions along the root in units of 2^-kMaxDepth: exact, so
        // neighbouring segments share their end parameter bit for bit.
        const int shift = glsl::kMaxDepth - depth;
        const double pa = span * (static_cast<double>(index << shift) * unit);
        const double pb = span * (static_cast<double>((index + 1u) << shift) * unit);
        const Footprint footprint = path.footprint(pa, pb);
        // Down to the floor (ending where the path leaves through it): may hit; above the
        // parent's bound: cannot; else the pyramid's bound over the footprint.
        bool mayHit = floorExit && pb == span;
        double bound = parentBound;
        if (!mayHit && footprint.lowest <= parentBound) {
            bound = std::min(bound, path.bound(footprint, stats));
            mayHit = footprint.lowest <= bound;
        }
        if (mayHit) {
            if (footprint.extent() <= glsl::kLeafTexels || depth >= glsl::kMaxDepth) {
                // From where a falling path comes down to the bound.
                const double from = path.descendTo(pa, pb, bound);
                if (auto hit = path.leaf(from, pb, stats)) return hit;
            } else {
                // The near half, or the far one when the near one lies above the bound.
                ++depth;
                index *= 2u;
                parentBound = bound;
                if (path.lowest(pa, 0.5 * (pa + pb)) > bound) ++index;
                continue;
            }
        }
        // On to index + 1 at this depth; after a far half cleared by a wide margin, one level
        // up (the next segment is a near half under another parent, whose bound is unknown).
        const bool farHalf = (index & 1u) == 1u;
        ++index;
        if ((index >> depth) != 0u) {
            // Leaving through the floor going down: the exit point is the hit.
            if (floorExit) return path.floorHit(stats);
            return std::nullopt;
        }
        if (farHalf) {
            parentBound = kNoBound;
            if (footprint.lowest - bound > 2.0 * footprint.drop) {
                index >>= 1;
                --depth;
            }
        }
    }
    stats.exhausted = true;
    return std::nullopt;
}

}  // namespace microrelief
