// microrelief-bench's measurements: for each method and knob setting, map and view, the
// frame times (GL timer queries, glFinish wall time and the process's CPU time; every
// setting of a map and view timed in the same rounds, a frame each in turn), texel fetches
// per pixel (the instrumented shader variant) and accuracy against the exact CPU reference.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "MapEntry.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/gl/GlContext.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief::bench {

struct BenchMap {
    std::string name;  // kResampledRelief, or the file's mapName; "-cylinder" etc. appended
    std::shared_ptr<const HeightMap> map;
    double heightScale = 0.1;
    BaseShape base = {};
    Interpolation interpolation = Interpolation::Bilinear;  // "-biquadratic" appended
};

struct Setting {
    MethodSettings method;
    std::string param;  // the knob as the CSV shows it: steps, pixel error, or "-"
    // The coarse pass's tile (ReliefRenderer::setCoarsePass), 0: the single pass. A row of
    // its own, "exact+coarseT", beside the multilevel method's exact one.
    int coarseTile = 0;
};

struct Measurement {
    std::string method, param, map;
    std::string base = "plane";
    std::string interpolation = "bilinear";
    int mapSize = 0;      // max(W, H)
    int viewDegrees = 0;  // between the view direction and the surface normal
    int width = 0, height = 0;
    double msMedian = 0.0;      // GL_TIME_ELAPSED
    double msWallMedian = 0.0;  // draw + glFinish on the CPU clock
    double msCpuMedian = 0.0;   // the process's CPU time, all its threads, draw + glFinish
    // Each timed frame's times, in round order: every setting of a map and view is timed
    // in the same rounds, a frame each in turn (Timing.h: interleavedOrder), so that frame
    // k of two rows of one map and view were drawn in the same round (pairedRatio).
    std::vector<double> gpuFrames, wallFrames, cpuFrames;
    double fetchesMean = 0.0;  // over pixels whose ray meets the relief's box
    double fetchesMax = 0.0;
    // The traversal's share of fetchesMean: reads of its bounds (a max pyramid, a cone map);
    // the rest read the samples (the last level, the surface).
    double boundFetchesMean = 0.0;
    // With the coarse pass: its own pyramid reads over the same pixels (its tiles' reads
    // summed, over the pixels whose ray meets the box), part of fetchesMean and of
    // boundFetchesMean; 0 without it.
    double coarseFetchesMean = 0.0;
    double coverageMismatchPct = 0.0;
    double offHalfTexelPct = 0.0;
    // The same two over the pixels whose rays come in through the top face: what the peers
    // that know no side walls or bottom face are measured by.
    double topCoverageMismatchPct = 0.0;
    double topOffHalfTexelPct = 0.0;
    double meanErrorPx = 0.0;  // hits' distance from the exact ones, in pixels there
    double p99ErrorPx = 0.0;
    double p99ErrorTexels = 0.0;  // the same distance in map texels
    double topP99ErrorTexels = 0.0;
    std::size_t exhausted = 0;
    double hitPct = 0.0;  // pixels whose exact ray hits the relief: the covered area
    // What the method costs on this map before its first frame: the GPU textures it reads
    // (the samples and its bounds), bytes per map texel, and the time to build its bounds
    // (the multilevel method's windows, maxmip's quadtree and cone's cone map on the GPU,
    // rcsm's on the CPU; none for the methods that read the samples alone), wall ms to
    // glFinish; and where a method's bounds are built on the CPU too (cone, rcsm), that
    // build's time (else negative: none).
    double bytesPerTexel = 0.0;
    double preprocessMs = 0.0;
    std::string preprocessWhere = "-";  // "gpu", "cpu", or "-": nothing to build
    double cpuPreprocessMs = -1.0;
};

struct BenchOptions {
    std::vector<int> mapSizes;
    std::vector<MapEntry> assets;  // extra maps (files)
    std::vector<int> viewDegrees;
    int width = 512, height = 512;
    int maxSteps = 4096;  // cap on the step budgets of steep, pom and relief
    int frames = 10;      // timed rounds (a frame of each setting) per map and view
    std::vector<Method> methods;
    std::vector<BaseShape> bases{BaseShape::plane()};  // each map on each base
    // Each map and base on each; the biquadratic surface with the exact methods only.
    std::vector<Interpolation> interpolations{Interpolation::Bilinear};
    // The shaders as GLSL 3.30 in a newer context (ReliefRenderer::setGlsl330): the path of
    // a GL 3.3 engine, against 4.00's gathers in another run on the same machine.
    bool glsl330 = false;
    // The coarse pass's tile sizes measured as rows of their own: the multilevel method's
    // exact frame on the plane (the pass's one case today) with each; empty: none.
    std::vector<int> coarseTiles{8};
};

// Why `method` is not measured on `m`, or "" where it is: on a curved base only the methods
// that run there; on the biquadratic surface the exact methods (multilevel, maxmip, cone),
// beside their bilinear rows; the cone-stepping peers only where their cone maps build in
// seconds to a minute on one core (peers/ConeMap.h, measured on llvmpipe's machine: cone up
// to 1024 texels a side, rcsm up to 512). The one test of what is measured: the run, its
// count and the report's "Not measured" lines all ask it.
std::string whyNotMeasured(Method method, const BenchMap& m);

// The knob settings measured for `method` on a map of `mapSize` texels: step budgets in
// powers of two from 8 to min(2 mapSize, maxSteps); pixel errors 0, 1 and 4 for the
// multilevel method, and its exact frame with the coarse pass of each of `coarseTiles`
// (the caller gives them where the pass applies); one setting for the others.
std::vector<Setting> settingsFor(Method method, int mapSize, int maxSteps,
                                 const std::vector<int>& coarseTiles = {});
// The coarse tiles that apply to a map: the options' on the plane, none on a curved base.
const std::vector<int>& coarseTilesFor(const BenchOptions& options, const BenchMap& m);

// Runs everything; `report` is called after each measurement (progress and the CSV).
void runBenchmark(GlContext& context, const BenchOptions& options,
                  const std::vector<BenchMap>& maps,
                  const std::function<void(const Measurement&)>& report);

// The benchmark's relief at n x n: procedural cobblestones (synth::cobbles, another seed
// than the bundled map), the same continuous relief at every size, with steep joints
// that step-based methods must not step over.
inline constexpr std::uint32_t kBenchReliefSeed = 7;
HeightMap benchRelief(int n);
inline const std::string kResampledRelief = "relief";

// The name a map goes by on a base and surface: "relief" on the plane, "relief-cylinder",
// "relief-biquadratic", "relief-sphere-biquadratic", ...
std::string mapOnBase(const std::string& name, const BaseShape& base,
                      Interpolation interpolation = Interpolation::Bilinear);

// A camera looking at the relief halfway up it, at a point of the base whose normal makes
// `degrees` with the view direction (0: straight at it), from 1.35 units away: on the plane
// the map's centre, seen from azimuth 35 degrees; on a curved base the point at u = 0.6
// on the equator (the middle of the column), tilted towards +y.
Camera viewCamera(int degrees, const BaseShape& base, double top);

}  // namespace microrelief::bench
