// Cone maps for the cone-stepping peers: `cone`, cone step mapping with cones
// that are conservative for the bilinear surface (J. Dummer, "Cone Step Mapping", 2006;
// robust cones as in "Robust Cone Step Mapping", EGSR 2024), built from the max pyramid
// (the idea of quick cone maps, Eurographics 2022); and `rcsm`, relaxed cone stepping
// (F. Policarpo, M. M. Oliveira, GPU Gems 3, ch. 18), built as published, not claimed
// conservative.
//
// Units, as map space has them (shaders/microrelief/map_space.glsl): X, Y in texels (texel
// square (i, j) is [i, i+1] x [j, j+1], sample (i, j) at its centre), heights in map height
// units (the samples' own). A ratio r is horizontal texels per map height unit. The height
// scale (--height-scale) does not enter the maps: it is in the map-space ray direction
// (dir.z = object dy / heightScale), so one cone map serves every height scale.
//
// The conservative cone of texel square T (buildConservativeConeMap), stored as (B_T, r_T):
//     K_T = { (x, z) : z >= B_T + dist(x, T) / r_T },
// dist the Euclidean distance in texels from the map point x to the square T (0 on T).
// B_T >= the bilinear surface's max over T (the pyramid's finest bound, MaxPyramid.h, then
// rounded up to a half float, at least 2^-14 where not 0: a normal half), and r_T is such that no
// point of the surface lies inside K_T's interior: for every map point x, h(x) <= B_T + dist(x, T)
// / r_T. (Cones of this shape, with the apex widened to the whole square at its bound, are what
// make stepping exact with nearest reads: a ray at any point of T at or above B_T that travels a
// horizontal distance s is at most s from T, so it stays above the surface while
// z > B_T + s / r_T; shaders/microrelief/cone_step.glsl.) The exact r_T is
//     r*_T = inf { dist(x, T) / (h(x) - B_T) : h(x) > B_T },
// capped at kConeRatioCap; the build gives at most r*_T and says how it bounds it (the
// .cpp: exact on the pieces level with T in a row or column, a tangent lower bound of the
// distance on the diagonal ones), then rounded down to a half float.
//
// The renderer builds this map on the GPU (gl/PyramidBuilder.h: buildConeMap), the same
// walk in floats with every rounding towards narrower cones: the same apexes, each ratio at
// most this build's (mostly the same; a few halves below where h - B is small beside h);
// this build is its reference in the tests.
//
// The relaxed cone of sample (i, j) (buildRelaxedConeMap), stored as (h(i, j), r): the
// published construction, a ray from the top of the relief box above the sample through
// every other sample's surface point, followed on under the surface (`searchSteps` steps
// down to height 0) to where it first comes out; the cone (apex at the sample, ratio r)
// must not hold that exit point. A ray entering the cone may then cross the surface once
// inside it, and a binary search finds the crossing. Samples read as the published tool
// reads them (bilinearly, between texel centres, clamped at the edges). Each ratio is at
// most relaxedRatioCap: the published build starts every cone at ratio 1 and keeps the
// smaller (its RGBA8 channel holds [0, 1]), a ratio in texture coordinates per unit of
// depth, one map width per map height unit.
//
// Both are kept as RG16F texels (4 bytes a texel), not the published RGBA8: 11 significant
// bits where 8-bit channels hold 256 levels of the height range, so a plateau rounded up
// (and a ratio rounded down) costs the cones at most 2^-11 relative, and the relaxed map's
// heights are 16 times closer to the surface they stand for.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief {

// The widest cone a build starts from: the largest finite half float (texels per map
// height unit). A texel with no higher surface anywhere keeps it, stored as 65472 (the
// half below, after the builds' margins).
inline constexpr float kConeRatioCap = 65504.0f;
// RG16F: plateau (or height) and ratio.
inline constexpr int kConeMapBytesPerTexel = 4;

struct ConeMap {
    int width = 0, height = 0;
    // Per texel, row-major: the apex height (B_T, conservative; the sample, relaxed) and
    // the ratio, both on the half-float grid (exactly what the GPU reads).
    std::vector<float> apex, ratio;

    float apexAt(int i, int j) const { return apex[static_cast<std::size_t>(j) * width + i]; }
    float ratioAt(int i, int j) const { return ratio[static_cast<std::size_t>(j) * width + i]; }
};

// How a build went: pyramid nodes (fast build) or texel squares (brute force) looked at.
struct ConeMapStats {
    std::uint64_t nodesVisited = 0;
};

// Called as a build goes, with the fraction of the map's rows done (after each row: 1 / H,
// 2 / H, ..., 1), on one of the building threads, one call at a time (the rows are built
// on the machine's cores; WebAssembly without threads builds on its one); it must not throw
// (a throw on a building thread ends the program): for a progress display
// (the web page's worker posts it to the page). Empty: nothing is called.
using ConeMapProgress = std::function<void(double done)>;

// The conservative cone map from the max pyramid: a branch-and-bound walk of its quadtree
// (MaxMipPyramid.h) per texel, nearest nodes first, pruning a node whose bound cannot narrow the
// cone (O(N^2 log N) on maps whose cones are narrow). Gives the same cones as the brute force,
// whose leaf computation it shares. Plane maps (clamped edges) only.
ConeMap buildConservativeConeMap(const HeightMap& map, ConeMapStats* stats = nullptr,
                                 const ConeMapProgress& progress = {});
// The same cones by brute force, every texel square against every texel square: O(N^4),
// the check of the fast build on small maps.
ConeMap buildConservativeConeMapBruteForce(const HeightMap& map);
// Before rounding to the half-float grid (doubles): the ratios both builds compute, for the
// tests that compare them.
std::vector<double> conservativeConeRatios(const HeightMap& map, bool bruteForce,
                                           ConeMapStats* stats = nullptr,
                                           const ConeMapProgress& progress = {});

// The published widest relaxed cone, ratio 1 in texture coordinates per unit depth, in
// texels per map height unit: the map's width (for a map that is not square, the smaller
// side: a cone here is round in texels, the published one round in texture coordinates).
double relaxedRatioCap(const HeightMap& map);

// The relaxed cone map (rcsm), as published (see above); the sample pairs that cannot
// narrow a cone are skipped by the same pyramid walk (a pair's ratio is at least the
// distance between the samples over their height difference), which changes no cone.
ConeMap buildRelaxedConeMap(const HeightMap& map, int searchSteps = 128,
                            ConeMapStats* stats = nullptr, const ConeMapProgress& progress = {});
// Its ratios before rounding, by the walk or by brute force (every pair), for the tests.
std::vector<double> relaxedConeRatios(const HeightMap& map, int searchSteps, bool bruteForce,
                                      ConeMapStats* stats = nullptr,
                                      const ConeMapProgress& progress = {});

// Half floats: the largest at most x, the smallest at least x (x >= 0; past the largest
// finite half, 65504 and infinity), and the bits of a value on the half grid.
float halfRoundedDown(double x);
float halfRoundedUp(double x);
std::uint16_t halfBits(float valueOnHalfGrid);
// The RG16F texels of a cone map, row-major, (apex, ratio) per texel.
std::vector<std::uint16_t> coneMapHalfTexels(const ConeMap& cones);

}  // namespace microrelief
