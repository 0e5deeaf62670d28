#include "microrelief/core/trace/Accuracy.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/core/ParallelRows.h"
#include "microrelief/core/trace/ReferenceTracer.h"

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

ReferencePicture traceReferencePicture(const CameraFrame& camera, const HeightMap& map,
                                       double heightScale, const BaseShape& base,
                                       Interpolation interpolation) {
    return traceReferencePicture(camera, ReliefGeometry{&map, heightScale, base, interpolation});
}

ReferencePicture traceReferencePicture(const CameraFrame& camera, const ReliefGeometry& relief) {
    const ReferenceTracer reference(relief);
    ReferencePicture picture;
    picture.width = camera.width;
    picture.texelsPerUnit = 1.0 / relief.base.texelSize(relief.map->width, relief.map->height);
    picture.worldToObject = glm::dmat3(relief.model.worldToObject());
    const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
    picture.hits.assign(count, std::nullopt);
    // The pixels are independent and the tracer keeps no state between rays, so bands of
    // rows are traced at once; the picture is the same however many threads ran. (viaTop
    // is a vector<bool>, whose neighbouring bits share a word: written after the bands.)
    std::vector<unsigned char> viaTop(count, 0);
    parallelEachRow(
        0, camera.height, camera.width,
        [&](int row) {
            for (int column = 0; column < camera.width; ++column) {
                const std::size_t pixel = static_cast<std::size_t>(row) * camera.width + column;
                const ReferenceHit exact = reference.trace(camera.pixelRay(column, row));
                if (exact) picture.hits[pixel] = exact.position;
                viaTop[pixel] = exact.entryFace == HitFace::None;
            }
        },
        1024);
    picture.viaTop.assign(viaTop.begin(), viaTop.end());
    return picture;
}

ReferencePicture traceSampledReferencePicture(const CameraFrame& camera,
                                              const std::function<ReferenceHit(const Ray&)>& trace,
                                              double texelsPerUnit, const glm::dmat3& worldToObject,
                                              int pixels) {
    if (pixels < 1) throwRuntime("traceSampledReferencePicture: at least one pixel");
    // The lattice's cell side s in pixels, and how many cells fit each way: about W H / s^2
    // = `pixels` in all, where a whole step (ceil(s)) could give a quarter of that.
    const double side =
        std::max(1.0, std::sqrt(static_cast<double>(camera.width) * camera.height / pixels));
    const auto cells = [&](int extent) {
        return std::clamp(static_cast<int>(std::lround(extent / side)), 1, extent);
    };
    const int columns = cells(camera.width), rows = cells(camera.height);
    ReferencePicture picture;
    picture.width = camera.width;
    picture.texelsPerUnit = texelsPerUnit;
    picture.worldToObject = worldToObject;
    const std::size_t count = static_cast<std::size_t>(camera.width) * camera.height;
    picture.hits.assign(count, std::nullopt);
    picture.viaTop.assign(count, true);
    picture.traced.assign(count, false);
    for (int b = 0; b < rows; ++b) {
        const int row = static_cast<int>((2LL * b + 1) * camera.height / (2LL * rows));
        for (int a = 0; a < columns; ++a) {
            const int column = static_cast<int>((2LL * a + 1) * camera.width / (2LL * columns));
            const std::size_t pixel = static_cast<std::size_t>(row) * camera.width + column;
            const ReferenceHit exact = trace(camera.pixelRay(column, row));
            if (exact) picture.hits[pixel] = exact.position;
            picture.viaTop[pixel] = exact.entryFace == HitFace::None;
            picture.traced[pixel] = true;
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
        reference.viaTop.size() != count ||
        (!reference.traced.empty() && reference.traced.size() != count))
        throwRuntime("measureAccuracy: the reference picture is not of this camera's size");
    Accuracy result;
    std::vector<double> errors, pixelErrors;
    const double pixelWidthPerUnit = camera.pixelWidthPerUnit();
    for (int row = 0; row < camera.height; ++row) {
        for (int column = 0; column < camera.width; ++column) {
            const std::size_t pixel = static_cast<std::size_t>(row) * reference.width + column;
            if (!reference.traced.empty() && !reference.traced[pixel]) continue;
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
            const double error = glm::length(reference.worldToObject * (tested.position - *exact)) *
                                 reference.texelsPerUnit;
            errors.push_back(error);
            const double pixelWidth = glm::length(*exact - camera.eye) * pixelWidthPerUnit;
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
                         const std::function<PixelHit(int, int, const Ray&)>& trace,
                         const BaseShape& base) {
    return measureAccuracy(camera, traceReferencePicture(camera, map, heightScale, base), trace);
}

Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const ReferencePicture& reference, AccuracyScope scope) {
    return measureAccuracy(
        camera, reference,
        [&](int column, int row, const Ray&) {
            return PixelHit{frame.positionAt(column, row)[3] > 0.5f,
                            frame.worldPositionAt(column, row),
                            frame.statsAt(column, row)[3] > 0.0f};
        },
        scope);
}

Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const HeightMap& map, double heightScale, const BaseShape& base,
                              AccuracyScope scope) {
    return compareWithReference(frame, camera, ReliefGeometry{&map, heightScale, base}, scope);
}

Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera,
                              const ReliefGeometry& relief, AccuracyScope scope) {
    return compareWithReference(frame, camera, traceReferencePicture(camera, relief), scope);
}

}  // namespace microrelief
