// twin_wasm.cpp: the CPU twin of the shader's traversal (microrelief::core's MultilevelTracer,
// unchanged) behind a C interface for JavaScript, compiled to WebAssembly by
// scripts/build.mjs (generated/twin_wasm.js). The package picks with it (src/twin.js,
// Relief.raycast, trace and traceRays): world rays taken into the relief's object space by
// its model transform (ModelTransform, in double), traced there, and the hits given back in
// the world as relief.js has them (pick.frag's fields). The tests compile this very file
// natively too (tests/three/PickTest.cpp), so that the WebAssembly twin and the native one
// are the same code on the same doubles and can be compared bit for bit.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/ModelTransform.h"
#include "microrelief/core/trace/MultilevelTracer.h"

using namespace microrelief;

namespace {

std::string lastError;
std::vector<std::unique_ptr<MultilevelTracer>> twins;  // handle k + 1 is twins[k]

MultilevelTracer* find(int handle) {
    if (handle < 1 || handle > static_cast<int>(twins.size())) return nullptr;
    return twins[handle - 1].get();
}

// pick.frag's kinds (relief_map.glsl: MR_RELIEF_*): 0 a miss, 1 the surface, 2 and 3 the
// plane's walls, 4 its bottom, 5 a cylinder's cap.
double kindOf(HitFace face) {
    switch (face) {
        case HitFace::Top: return 1.0;
        case HitFace::WallX: return 2.0;
        case HitFace::WallZ: return 3.0;
        case HitFace::Bottom: return 4.0;
        case HitFace::Cap: return 5.0;
        case HitFace::None: break;
    }
    return 0.0;
}

}  // namespace

extern "C" {

// A twin of the relief over `samples` (width x height floats, row 0 first): its height
// scale, base (the name of a row of the table of bases, BaseType.h: "plane", "sphere"; its
// sizes' numbers, `sizeCount` of them, in the row's order, each size's `count`: a cylinder's
// radius and length, an ellipsoid's three radii, a sphere's radius) and last level
// (MR_INTERPOLATION_*). The twin copies the map and builds its max pyramid (half bounds, the
// GPU's texels). A handle, or 0 with mr_twin_last_error() saying why (heightMapFromSamples's,
// the table's and BaseShape's messages).
int mr_twin_create(const float* samples, int width, int height, double heightScale,
                   const char* base, const double* sizes, int sizeCount, int interpolation) {
    try {
        const HeightMap map = heightMapFromSamples(samples, width, height,
                                                   static_cast<std::size_t>(width) * sizeof(float),
                                                   {}, "the height map");
        // The row by its name, its sizes written into its defaults in its order, as twin.js
        // reads them from the shape (relief_core.js: baseSizeNumbers); `interpolation` is the
        // GLSL's value (variants.glsl), as twin.js gives it from relief_layout.js.
        const BaseType& type = baseType(std::string_view(base));
        BaseShape shape = type.defaults;
        int at = 0;
        for (const BaseSize& size : type.sizes) {
            if (at + size.count <= sizeCount) size.write(shape, sizes + at);
            at += size.count;
        }
        if (at != sizeCount)
            throwBadInput("the base " + std::string(type.name) + " has " + std::to_string(at) +
                          " size numbers, not " + std::to_string(sizeCount));
        validateBaseShape(shape);
        twins.push_back(std::make_unique<MultilevelTracer>(
            map, heightScale, shape,
            interpolation == glsl::kInterpolationBiquadratic ? Interpolation::Biquadratic
                                                             : Interpolation::Bilinear));
        return static_cast<int>(twins.size());
    } catch (const std::exception& e) {
        lastError = e.what();
        return 0;
    }
}

// The bytes the twin holds: its copy of the samples and its pyramid (blocks and windows,
// floats).
double mr_twin_bytes(int handle) {
    const MultilevelTracer* twin = find(handle);
    if (!twin) return 0.0;
    double bytes = static_cast<double>(twin->map().samples.size() * sizeof(float));
    const MaxPyramid& p = twin->pyramid();
    for (int k = 0; k < p.windowLevelCount(); ++k)
        bytes += static_cast<double>((p.windowLevelData(k).size() + p.blockLevelData(k).size()) *
                                     sizeof(float));
    return bytes;
}

// Traces `count` world rays: origins and directions 3 n doubles, ranges 2 n (tMin, tMax, in
// units of each direction's length), the model transform `model` (16 doubles, column-major,
// three's Matrix4.elements: object to world). Writes 12 doubles a ray into `out`: t, kind,
// exhausted, the world hit (origin + t direction), the world unit normal (the model's inverse
// transpose), uv (three's convention: 1 - v), iterations; a miss or a ray out of budget has
// its kind (0), exhausted, iterations and zeros. Returns 1, or 0 with mr_twin_last_error()
// saying why (an unknown handle, a model that is not an invertible affine transform).
int mr_twin_trace(int handle, const double* model, int count, const double* origins,
                  const double* directions, const double* ranges, double* out) {
    const MultilevelTracer* twin = find(handle);
    if (!twin) {
        lastError = "no such twin (released?)";
        return 0;
    }
    try {
        glm::dmat4 matrix(1.0);
        for (int column = 0; column < 4; ++column)
            for (int row = 0; row < 4; ++row) matrix[column][row] = model[4 * column + row];
        const ModelTransform transform(matrix);
        for (int k = 0; k < count; ++k) {
            const Ray world{{origins[3 * k], origins[3 * k + 1], origins[3 * k + 2]},
                            {directions[3 * k], directions[3 * k + 1], directions[3 * k + 2]}};
            const RayQuery query{ranges[2 * k], ranges[2 * k + 1], false};
            TraversalStats stats;
            const std::optional<ReliefHit> hit =
                twin->intersect(transform.toObject(world), query, &stats);
            double* o = out + 12 * k;
            for (int f = 0; f < 12; ++f) o[f] = 0.0;
            o[2] = stats.exhausted ? 1.0 : 0.0;
            o[11] = stats.iterations;
            if (!hit) continue;
            const glm::dvec3 point = world.origin + hit->t * world.direction;
            const glm::dvec3 normal = transform.normalToWorld(hit->normal);
            o[0] = hit->t;
            o[1] = kindOf(hit->face);
            o[3] = point.x, o[4] = point.y, o[5] = point.z;
            o[6] = normal.x, o[7] = normal.y, o[8] = normal.z;
            o[9] = hit->uv.x, o[10] = 1.0 - hit->uv.y;
        }
        return 1;
    } catch (const std::exception& e) {
        lastError = e.what();
        return 0;
    }
}

void mr_twin_release(int handle) {
    if (find(handle)) twins[handle - 1].reset();
}

// How many twins are held (not released): for the tests of ReliefMap.dispose.
int mr_twin_count() {
    int held = 0;
    for (const auto& twin : twins) held += twin ? 1 : 0;
    return held;
}

const char* mr_twin_last_error() { return lastError.c_str(); }
}
