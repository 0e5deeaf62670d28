#include "trace/Accuracy.h"

#include <algorithm>
#include <sstream>
#include <vector>

#include "trace/ReferenceTracer.h"

namespace microrelief {

std::string Accuracy::summary() const {
    std::ostringstream out;
    out << pixels << " px, " << referenceHits << " reference hits; hit/miss disagree " << coverageMismatches << " ("
        << coverageMismatchPercent() << " %); off > 0.5 texel " << offHalfTexel << " (" << offHalfTexelPercent()
        << " %); error p99 " << p99ErrorTexels << ", max " << maxErrorTexels << " texels; out of budget "
        << exhausted;
    return out.str();
}

Accuracy measureAccuracy(const CameraFrame& camera, const HeightMap& map, double heightScale,
                         const std::function<PixelHit(int, int, const Ray&)>& trace) {
    Accuracy result;
    const ReferenceTracer reference(ReliefGeometry{&map, heightScale});
    const double texelsPerUnit = std::max(map.width, map.height);
    std::vector<double> errors;
    for (int row = 0; row < camera.height; ++row) {
        for (int column = 0; column < camera.width; ++column) {
            ++result.pixels;
            const Ray ray = camera.pixelRay(column, row);
            const PixelHit tested = trace(column, row, ray);
            const ReferenceHit exact = reference.trace(ray);
            result.exhausted += tested.exhausted;
            if (exact) ++result.referenceHits;
            if (tested.hit != static_cast<bool>(exact)) {
                ++result.coverageMismatches;
                continue;
            }
            if (!tested.hit) continue;
            const double error = glm::length(tested.position - exact.position) * texelsPerUnit;
            errors.push_back(error);
            if (error > 0.5) ++result.offHalfTexel;
            result.maxErrorTexels = std::max(result.maxErrorTexels, error);
        }
    }
    if (!errors.empty()) {
        const std::size_t k = std::min(errors.size() - 1, static_cast<std::size_t>(0.99 * errors.size()));
        std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
        result.p99ErrorTexels = errors[k];
    }
    return result;
}

Accuracy compareWithReference(const RenderedFrame& frame, const CameraFrame& camera, const HeightMap& map,
                              double heightScale) {
    return measureAccuracy(camera, map, heightScale, [&](int column, int row, const Ray&) {
        const float* p = frame.positionAt(column, row);
        return PixelHit{p[3] > 0.5f, glm::dvec3(p[0], p[1], p[2]), frame.statsAt(column, row)[3] > 0.0f};
    });
}

}  // namespace microrelief
