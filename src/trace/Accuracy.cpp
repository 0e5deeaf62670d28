#include "trace/Accuracy.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "core/Error.h"
#include "trace/ReferenceTracer.h"

namespace microrelief {

std::string Accuracy::summary() const {
    std::ostringstream out;
    out << pixels << " px, " << referenceHits << " reference hits; hit/miss disagree "
        << coverageMismatches << " (" << coverageMismatchPercent() << " %); off > 0.5 texel "
        << offHalfTexel << " (" << offHalfTexelPercent() << " %); error p99 " << p99ErrorTexels
        << ", max " << maxErrorTexels << " texels, mean " << meanErrorPixels << " px, p99 "
        << p99ErrorPixels << " px; out of budget " << exhausted;
    return out.str();
}

namespace {

// Whether `ray` comes into the box [lo, hi] through a side wall or the bottom face: the
// slab it enters last is x, z, or y from below, at a point in front of the origin.
bool entersThroughSideOrBottom(const Ray& ray, const glm::dvec3& lo, const glm::dvec3& hi) {
    double tEnter = -1e300, tExit = 1e300;
    int entryAxis = -1;
    for (int axis = 0; axis < 3; ++axis) {
        const double o = ray.origin[axis], d = ray.direction[axis];
        if (d == 0.0) {
            if (o < lo[axis] || o > hi[axis]) return false;  // misses the box
            continue;
        }
        double t0 = (lo[axis] - o) / d, t1 = (hi[axis] - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > tEnter) {
            tEnter = t0;
            entryAxis = axis;
        }
        tExit = std::min(tExit, t1);
    }
    if (tEnter > tExit || tExit < 0.0 || tEnter < 0.0) return false;  // misses, or starts inside
    return entryAxis != 1 || ray.direction.y > 0.0;
}

}  // namespace

ReferencePicture traceReferencePicture(const CameraFrame& camera, const HeightMap& map,
                                       double heightScale) {
    const ReferenceTracer reference(ReliefGeometry{&map, heightScale});
    const double longer = std::max(map.width, map.height);
    const glm::dvec3 hi(0.5 * map.width / longer, heightScale * map.maxValue(),
                        0.5 * map.height / longer);
    const glm::dvec3 lo(-hi.x, 0.0, -hi.z);
    ReferencePicture picture;
    picture.width = camera.width;
    picture.texelsPerUnit = longer;
    picture.hits.reserve(static_cast<std::size_t>(camera.width) * camera.height);
    for (int row = 0; row < camera.height; ++row) {
        for (int column = 0; column < camera.width; ++column) {
            const Ray ray = camera.pixelRay(column, row);
            const ReferenceHit exact = reference.trace(ray);
            picture.hits.push_back(exact ? std::optional<glm::dvec3>(exact.position)
                                         : std::nullopt);
            picture.viaTop.push_back(!entersThroughSideOrBottom(ray, lo, hi));
        }
    }
    return picture;
}

namespace {

// The 99th percentile of `values` (reordered), 0 for none.
double percentile99(std::vector<double>& values) {
    if (values.empty()) return 0.0;
    const std::size_t k =
        std::min(values.size() - 1, static_cast<std::size_t>(0.99 * values.size()));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

}  // namespace

Accuracy measureAccuracy(const CameraFrame& camera, const ReferencePicture& reference,
                         const std::function<PixelHit(int, int, const Ray&)>& trace,
                         AccuracyScope scope) {
    const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
    if (reference.width != camera.width || reference.hits.size() != count ||
        reference.viaTop.size() != count)
        throwRuntime("measureAccuracy: the reference picture is not of this camera's size");
    Accuracy result;
    std::vector<double> errors, pixelErrors;
    // The centre pixel's width per unit of distance (CameraFrame::up is scaled by
    // tan(fovy / 2)), as the shader's level-of-detail cone has it (relief.frag).
    const double pixelAngle = 2.0 * glm::length(camera.up) / camera.height;
    for (int row = 0; row < camera.height; ++row) {
        for (int column = 0; column < camera.width; ++column) {
            const std::size_t pixel = static_cast<std::size_t>(row) * reference.width + column;
            if (scope == AccuracyScope::TopSurface && !reference.viaTop[pixel]) continue;
            ++result.pixels;
            const PixelHit tested = trace(column, row, camera.pixelRay(column, row));
            const std::optional<glm::dvec3>& exact = reference.hits[pixel];
            result.exhausted += tested.exhausted;
            if (exact) ++result.referenceHits;
            if (tested.hit != exact.has_value()) {
                ++result.coverageMismatches;
                continue;
            }
            if (!tested.hit) continue;
            const double error = glm::length(tested.position - *exact) * reference.texelsPerUnit;
            errors.push_back(error);
            const double pixelWidth = glm::length(*exact - camera.eye) * pixelAngle;
            pixelErrors.push_back(glm::length(tested.position - *exact) /
                                  std::max(pixelWidth, 1e-12));
            if (error > 0.5) ++result.offHalfTexel;
            result.maxErrorTexels = std::max(result.maxErrorTexels, error);
        }
    }
    result.p99ErrorTexels = percentile99(errors);
    if (!pixelErrors.empty()) {
        double sum = 0.0;
        for (double e : pixelErrors) sum += e;
        result.meanErrorPixels = sum / pixelErrors.size();
    }
    result.p99ErrorPixels = percentile99(pixelErrors);
    return result;
}

Accuracy measureAccuracy(const CameraFrame& camera, const HeightMap& map, double heightScale,
                         const std::function<PixelHit(int, int, const Ray&)>& trace) {
    return measureAccuracy(camera, traceReferencePicture(camera, map, heightScale), trace);
}

Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const ReferencePicture& reference, AccuracyScope scope) {
    return measureAccuracy(
        camera, reference,
        [&](int column, int row, const Ray&) {
            const float* p = frame.positionAt(column, row);
            return PixelHit{p[3] > 0.5f, glm::dvec3(p[0], p[1], p[2]),
                            frame.statsAt(column, row)[3] > 0.0f};
        },
        scope);
}

Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const HeightMap& map, double heightScale) {
    return compareWithReference(frame, camera, traceReferencePicture(camera, map, heightScale));
}

}  // namespace microrelief
