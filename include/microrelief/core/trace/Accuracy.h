// Measuring a tracer against the exact CPU reference (core/trace/ReferenceTracer.h) over the
// pixels of a picture: hit/miss disagreements, positions off by more than half a
// texel, error percentiles in texels and pixels, traversals that ran out of budget.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/gl/RenderedFrame.h"
#include "microrelief/core/trace/ReferenceTracer.h"

namespace microrelief {

// A tracer's answers against the exact reference, pixel by pixel: the figures of the
// accuracy sweep and of microrelief-render --compare-reference.
struct Accuracy {
    std::size_t pixels = 0;
    std::size_t referenceHits = 0;
    std::size_t coverageMismatches = 0;  // hit on one side, miss on the other
    std::size_t offHalfTexel = 0;        // both hit, positions further apart than half a texel
    std::size_t exhausted = 0;           // pixels that ran out of the iteration budget
    double maxErrorTexels = 0.0;
    double p99ErrorTexels = 0.0;
    // The same distances in pixels: over the width of a pixel's cone at the exact hit's
    // distance from the eye (what a level-of-detail tolerance is stated in).
    double meanErrorPixels = 0.0;
    double p99ErrorPixels = 0.0;

    double coverageMismatchPercent() const {
        return pixels ? 100.0 * coverageMismatches / pixels : 0.0;
    }
    double offHalfTexelPercent() const {
        return referenceHits ? 100.0 * offHalfTexel / referenceHits : 0.0;
    }
    std::string summary() const;
};

// One pixel's answer from the tracer under test.
struct PixelHit {
    bool hit = false;
    glm::dvec3 position{0.0};
    bool exhausted = false;
};

// The exact reference's answer for every pixel of a camera's picture, traced once and
// reusable for any number of tracers of the same view.
struct ReferencePicture {
    int width = 0;
    // Errors are reported in texels of the relief's object space: 1 / BaseShape::texelSize
    // (max(W, H) on the plane) per object unit, a world difference taken there first by
    // the model's inverse (a relief grown 1e5 times has texels 1e5 times as wide).
    double texelsPerUnit = 1.0;
    glm::dmat3 worldToObject{1.0};
    std::vector<std::optional<glm::dvec3>> hits;  // row-major, world positions
    // Row-major: the pixel's ray does not come into the relief's box through a side wall
    // or the bottom face (it comes through the top face, starts inside, or misses the box).
    std::vector<bool> viaTop;
    // Row-major: the pixels traced; empty where every one was (traceSampledReferencePicture
    // traces some). A comparison takes in the traced pixels alone.
    std::vector<bool> traced;
};

// Which pixels a comparison takes in: all of them, or those whose rays do not come in
// through a side wall or the bottom face (AccuracyScope::TopSurface), for methods that
// know no side walls or bottom face: their hits and misses where the top surface is all
// the ray can meet, false hits included (what can be asked of them).
enum class AccuracyScope { AllPixels, TopSurface };
ReferencePicture traceReferencePicture(const CameraFrame& camera, const ReliefGeometry& relief);
// The reference on about `pixels` pixels of the camera's picture, spread evenly: a
// lattice of round(W / s) columns by round(H / s) rows (at least one each), s = sqrt(W H /
// pixels), each pixel at the middle of its cell (every pixel where s <= 1), traced by
// `trace` (a PagedReferenceTracer's, for
// a map not in memory whole, whose reads from disk are what costs), errors in texels at
// `texelsPerUnit` of the relief's object space (1 / BaseShape::texelSize) after
// `worldToObject` (the model's inverse).
ReferencePicture traceSampledReferencePicture(const CameraFrame& camera,
                                              const std::function<ReferenceHit(const Ray&)>& trace,
                                              double texelsPerUnit, const glm::dmat3& worldToObject,
                                              int pixels = 4096);
ReferencePicture traceReferencePicture(const CameraFrame& camera, const HeightMap& map,
                                       double heightScale, const BaseShape& base = {},
                                       Interpolation interpolation = Interpolation::Bilinear);

// Every pixel of `camera`'s picture: `trace(column, row, ray)` against the reference.
// Errors are measured in texels of the map: world distance * max(W, H).
Accuracy measureAccuracy(const CameraFrame& camera, const ReferencePicture& reference,
                         const std::function<PixelHit(int, int, const Ray&)>& trace,
                         AccuracyScope scope = AccuracyScope::AllPixels);
Accuracy measureAccuracy(const CameraFrame& camera, const HeightMap& map, double heightScale,
                         const std::function<PixelHit(int, int, const Ray&)>& trace,
                         const BaseShape& base = {});

// A rendered frame's AOV against the reference.
Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const ReferencePicture& reference,
                              AccuracyScope scope = AccuracyScope::AllPixels);
Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const ReliefGeometry& relief,
                              AccuracyScope scope = AccuracyScope::AllPixels);
Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const HeightMap& map, double heightScale, const BaseShape& base = {},
                              AccuracyScope scope = AccuracyScope::AllPixels);

}  // namespace microrelief
