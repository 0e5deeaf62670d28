// The accuracy sweep of issue 3: maps that defeat step-based methods (noise, one-texel
// spikes and walls, cliffs), degenerate and odd maps, maps read from 16-bit and float
// files, a 4096 x 4096 map; each seen from 90 degrees down to 1 degree above the
// surface at several azimuths, and from the awkward places (inside the box, below the
// base plane, far away, very close).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/core/trace/MultilevelTracer.h"

namespace microrelief::test {

struct SweepMap {
    std::string name;
    std::shared_ptr<const HeightMap> map;
    double heightScale;
    BaseShape base = {};  // the plane, a cylinder or an ellipsoid (issue 11)
    Interpolation interpolation = Interpolation::Bilinear;  // the last level (issue 12)

    ReliefGeometry geometry() const { return {map.get(), heightScale, base, interpolation}; }
};

struct SweepView {
    std::string name;
    Camera camera;
};

struct SweepCase {
    const SweepMap* map;
    SweepView view;
    std::string name() const { return map->name + "_" + view.name; }
};

// Built once per process (the 4096 map takes a moment); `scratch` holds the files the
// 16-bit and float maps are written to and read back from. The plane's maps first, then
// the curved bases' (each map on a cylinder and on an ellipsoid or a sphere), then a
// share of both on the biquadratic surface (named "..._biquadratic").
const std::vector<SweepMap>& sweepMaps();
// How many maps sweepMaps() holds and their names, without building them.
std::size_t sweepMapCount();
std::string sweepMapName(std::size_t k);
std::vector<SweepView> sweepViews(const SweepMap& map);
std::vector<SweepCase> sweepCases();

// Picture size for a case: small, since every pixel is also traced on the CPU.
constexpr int kSweepSize = 64;

// The budgets every case is held to (issue 3), on every backend and for the CPU twin:
// hit/miss may differ only for rays that graze a ridge or a silhouette exactly (float on
// the GPU, double in the reference), at most 0.1 % of pixels; a position off by more
// than half a texel only where such a ray lands on a farther surface, at most 0.2 % of
// hit pixels; no ray may run out of the iteration budget.
constexpr double kMaxCoverageMismatchPercent = 0.1;
constexpr double kMaxOffHalfTexelPercent = 0.2;

// Sparse maps seen at grazing angles (the spikes at 1 and 3 degrees) hit only a few
// hundred of the 4096 pixels, where 0.2 % is less than one pixel: one ray that grazes a
// spike's tip in float and passes it in double would fail the case. Such a case may
// have one off pixel; a second one fails it.
inline bool withinOffBudget(const Accuracy& a) {
    return a.offHalfTexel <= 1 || a.offHalfTexelPercent() <= kMaxOffHalfTexelPercent;
}

// The CPU twin's answer for one pixel, in the form measureAccuracy takes.
PixelHit twinPixel(const MultilevelTracer& twin, const Ray& ray);

}  // namespace microrelief::test
