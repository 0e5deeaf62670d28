#include "Benchmark.h"

#include "Timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/ReliefTextures.h"

namespace microrelief::bench {

namespace {

bool rayMeetsBox(const Ray& ray, const glm::dvec3& lo, const glm::dvec3& hi) {
    double t0 = 0.0, t1 = 1e300;
    for (int a = 0; a < 3; ++a) {
        if (ray.direction[a] == 0.0) {
            if (ray.origin[a] < lo[a] || ray.origin[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - ray.origin[a]) / ray.direction[a],
               tb = (hi[a] - ray.origin[a]) / ray.direction[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1;
}

// Which pixels' rays meet the relief's box: the pixels the fetch means are taken over.
std::vector<bool> pixelsInBox(const CameraFrame& camera, const ReliefExtent& extent) {
    const glm::dvec3 lo = extent.min, hi = extent.max;
    std::vector<bool> inBox;
    inBox.reserve(static_cast<std::size_t>(camera.width) * camera.height);
    for (int row = 0; row < camera.height; ++row) {
        for (int column = 0; column < camera.width; ++column)
            inBox.push_back(rayMeetsBox(camera.pixelRay(column, row), lo, hi));
    }
    return inBox;
}

struct MethodCost {
    double bytesPerTexel = 0.0, preprocessMs = 0.0, cpuPreprocessMs = -1.0;
    std::string where = "-";
};

// What each method of `methods` that runs on this map needs before its first frame: its
// bounds built (timed here, before the method is first set, which would build them
// untimed) and the bytes of the textures it reads. The multilevel method's windows,
// maxmip's quadtree and cone's cone map: median of three GPU builds after a warm-up (a
// build of a second or more: that one); a cone map on the CPU (cone's beside its GPU
// build, rcsm's the only one): one build (seconds), the samples read back and the map
// uploaded included.
std::map<Method, MethodCost> measureCosts(const GL& gl, ReliefRenderer& renderer,
                                          const std::vector<Method>& methods, const BenchMap& m) {
    ReliefTextures& textures = *renderer.textures();
    PyramidBuilder& builder = renderer.pyramidBuilder();
    const auto medianOfThree = [&](const std::function<void()>& build) {
        // The first build warms up; one of a second or more is its own measure (a cone
        // map on llvmpipe: 18 s at 1024), which three more would not change.
        const double first = wallMs(gl, build);
        if (first >= 1000.0) return first;
        std::vector<double> ms;
        for (int k = 0; k < 3; ++k) ms.push_back(wallMs(gl, build));
        return median(ms);
    };
    std::map<Method, MethodCost> costs;
    const double texels = static_cast<double>(m.map->width) * m.map->height;
    const double samples = textureBytes(gl, textures.samples()) / texels;
    for (Method method : methods) {
        if (!whyNotMeasured(method, m).empty()) continue;
        MethodCost cost;
        cost.bytesPerTexel = samples;
        if (method == Method::Multilevel) {
            // Before maxmip's quadtree is made: build() makes both where both are there.
            if (!textures.hasMaxMipPyramid())
                cost.preprocessMs = medianOfThree([&] { builder.build(textures); });
            cost.where = "gpu";
            cost.bytesPerTexel += textureBytes(gl, textures.windowPyramid()) / texels;
        } else if (method == Method::MaxMip) {
            if (!textures.hasMaxMipPyramid()) textures.addMaxMipPyramid(gl, builder);
            cost.preprocessMs = medianOfThree([&] { builder.buildAligned(textures); });
            cost.where = "gpu";
            cost.bytesPerTexel += textureBytes(gl, textures.maxPyramid()) / texels;
        } else if (method == Method::Cone) {
            // The CPU build first, then the GPU's, whose map the frames read.
            const auto kind = ReliefTextures::ConeKind::Conservative;
            textures.dropConeMap(kind);
            cost.cpuPreprocessMs = wallMs(gl, [&] { textures.addConeMap(gl, kind); });
            cost.preprocessMs = medianOfThree([&] { builder.buildConeMap(textures); });
            cost.where = "gpu";
            cost.bytesPerTexel += textureBytes(gl, textures.coneMap(kind)) / texels;
        } else if (method == Method::Rcsm) {
            const auto kind = ReliefTextures::ConeKind::Relaxed;
            if (!textures.coneMap(kind)) {
                cost.preprocessMs = wallMs(gl, [&] { textures.addConeMap(gl, kind); });
                cost.cpuPreprocessMs = cost.preprocessMs;
            }
            cost.where = "cpu";
            cost.bytesPerTexel += textureBytes(gl, textures.coneMap(kind)) / texels;
        }
        costs[method] = cost;
    }
    return costs;
}

}  // namespace

HeightMap benchRelief(int n) {
    return synth::cobbles(n, n, kBenchReliefSeed);
}

std::string mapOnBase(const std::string& name, const BaseShape& base, Interpolation interpolation) {
    return (base.curved() ? name + "-" + baseName(base) : name) +
           (interpolation == Interpolation::Biquadratic ? "-biquadratic" : "");
}

std::string whyNotMeasured(Method method, const BenchMap& m) {
    if (!methodRunsOnBase(method, m.base))
        return "not on curved bases (they take multilevel, maxmip, pom and relief)";
    if (m.interpolation == Interpolation::Biquadratic && method != Method::Multilevel &&
        method != Method::MaxMip && method != Method::Cone)
        return "not on the biquadratic level (measured there: the exact methods, multilevel, "
               "maxmip and cone)";
    const int side = std::max(m.map->width, m.map->height);
    const int largest = method == Method::Cone ? 1024 : method == Method::Rcsm ? 512 : side;
    if (side > largest)
        return "not on " + m.name + " (" + std::to_string(side) + " texels a side; " +
               (method == Method::Rcsm
                    ? "rcsm up to 512: its relaxed cone map is built on the CPU, as "
                      "published, and takes minutes past that)"
                    : "cone up to 1024: its cone map takes tens of seconds past that on "
                      "llvmpipe)");
    return {};
}

Camera viewCamera(int degrees, const BaseShape& base, double top) {
    const double tilt = glm::radians(static_cast<double>(degrees));
    Camera camera;
    camera.fovyDegrees = 45.0;
    if (!base.curved()) {
        const double elevation = glm::radians(90.0 - degrees), azimuth = glm::radians(35.0);
        camera.target = {0.0, 0.5 * top, 0.0};
        camera.eye = camera.target + 1.35 * glm::dvec3(std::cos(elevation) * std::cos(azimuth),
                                                       std::sin(elevation),
                                                       std::cos(elevation) * std::sin(azimuth));
        camera.up = degrees == 0 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
        return camera;
    }
    // u = 0.6 on the equator: the frame direction (sin phi, 0, cos phi), phi = 36 degrees.
    const double phi = 2.0 * 3.14159265358979 * (0.6 - 0.5);
    const glm::dvec3 scale = base.frameScale(), out(std::sin(phi), 0.0, std::cos(phi));
    camera.target = (1.0 + 0.5 * top) * out * scale;
    const glm::dvec3 normal = glm::normalize(out / scale), up(0.0, 1.0, 0.0);
    camera.eye = camera.target + 1.35 * (std::cos(tilt) * normal + std::sin(tilt) * up);
    camera.up = -std::sin(tilt) * normal + std::cos(tilt) * up;  // square to the view
    return camera;
}

std::vector<Setting> settingsFor(Method method, int mapSize, int maxSteps,
                                 const std::vector<int>& coarseTiles) {
    std::vector<Setting> settings;
    MethodSettings s;
    s.method = method;
    if (method == Method::Multilevel) {
        for (float error : {0.0f, 1.0f, 4.0f}) {
            s.pixelError = error;
            settings.push_back(
                {s, error == 0.0f ? "exact" : std::to_string(static_cast<int>(error)) + "px"});
            if (error != 0.0f) continue;
            for (int tile : coarseTiles)
                settings.push_back({s, "exact+coarse" + std::to_string(tile), tile});
        }
    } else if (method == Method::Rcsm) {
        // 15 relaxed cone steps and 8 binary steps as published, then more cone steps.
        for (int steps = 15; steps <= std::min(2 * mapSize, maxSteps); steps *= 2) {
            s.steps = steps;
            s.refineSteps = 8;
            settings.push_back({s, std::to_string(steps)});
        }
    } else if (methodHasSteps(method)) {
        for (int steps = 8; steps <= std::min(2 * mapSize, maxSteps); steps *= 2) {
            s.setSteps(steps);
            settings.push_back({s, std::to_string(steps)});
        }
    } else {
        settings.push_back({s, method == Method::MaxMip || method == Method::Cone ? "exact" : "-"});
    }
    return settings;
}

const std::vector<int>& coarseTilesFor(const BenchOptions& options, const BenchMap& m) {
    static const std::vector<int> none;
    return m.base.kind == BaseKind::Plane ? options.coarseTiles : none;
}

namespace {

// The coarse pass's own reads in its last draw (ReliefRenderer::coarseStartTexture: a texel
// a tile, y its pyramid reads), summed over the tiles.
double coarsePassReads(const GL& gl, const ReliefRenderer& renderer) {
    if (!renderer.coarsePassDrawn()) return 0.0;
    GLint width = 0, height = 0, previous = 0;
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
    gl.BindTexture(GL_TEXTURE_2D, renderer.coarseStartTexture());
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &height);
    std::vector<float> texels(static_cast<std::size_t>(width) * height * 4);
    gl.GetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, texels.data());
    gl.BindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous));
    // The texture may be larger than the tiles drawn (it grows, never shrinks).
    const glm::ivec2 used = renderer.coarseStartSize();
    double sum = 0.0;
    for (int y = 0; y < used.y; ++y)
        for (int x = 0; x < used.x; ++x)
            sum += texels[(static_cast<std::size_t>(y) * width + x) * 4 + 1];
    return sum;
}

}  // namespace

void runBenchmark(GlContext& context, const BenchOptions& options,
                  const std::vector<BenchMap>& maps,
                  const std::function<void(const Measurement&)>& report) {
    context.makeCurrent();
    const GL& gl = context.gl();
    ReliefRenderer renderer(gl, shaderDirectory());
    renderer.setGlsl330(options.glsl330);
    OffscreenTarget target(gl, options.width, options.height);
    Timer timer(gl);
    const ShadingOptions shading;
    bool firstView = true;

    for (const BenchMap& m : maps) {
        ReliefDesc relief;
        relief.base = m.base;
        relief.interpolation = m.interpolation;
        relief.heightScale = static_cast<float>(m.heightScale);
        renderer.apply(relief, MethodSettings{}, m.map.get(), m.name);  // runs on every base
        const int mapSize = std::max(m.map->width, m.map->height);
        const std::map<Method, MethodCost> costs = measureCosts(gl, renderer, options.methods, m);
        const ReliefExtent extent = reliefExtent(*m.map, m.heightScale, m.base);
        // Every setting of every method measured on this map, in the report's order.
        std::vector<std::pair<Method, Setting>> settings;
        for (Method method : options.methods) {
            if (!whyNotMeasured(method, m).empty()) continue;
            for (const Setting& setting :
                 settingsFor(method, mapSize, options.maxSteps, coarseTilesFor(options, m)))
                settings.emplace_back(method, setting);
        }
        for (int degrees : options.viewDegrees) {
            const CameraFrame camera =
                resolveCamera(viewCamera(degrees, m.base, extent.topHeight), options.width,
                              options.height, sceneRadius(extent));
            const ReferencePicture reference = traceReferencePicture(
                camera, ReliefGeometry{m.map.get(), m.heightScale, m.base, m.interpolation});
            const std::vector<bool> inBox = pixelsInBox(camera, extent);
            std::size_t referenceHits = 0;
            for (const auto& hit : reference.hits) referenceHits += hit.has_value();
            auto draw = [&] {
                target.clear(glm::vec3(0.0f));
                renderer.draw(camera, shading);
            };
            std::vector<Measurement> rows(settings.size());

            // Timing: every setting in the same rounds, a frame each in turn (Timing.h:
            // interleavedOrder), so that a slow spell of a shared machine falls on them
            // alike and the ratios between them hold still from run to run (issue 52: the
            // settings timed one after another, ten frames each, gave the rock wall's cone
            // ratio 1.14x and then 0.59x a few minutes apart). Before the rounds each
            // setting draws twice (its program and llvmpipe's variant of it made), then
            // all draw in turn for 300 ms, 500 ms in the run's first view: the frames right
            // after start-up ran up to 1.7x slow on llvmpipe; the first frames after the
            // reference's trace on every core up to 10 % slow there (2026-12-05); and a
            // GPU idle while the CPU traced the reference ran up to 5.4x slow after it, at
            // lowered clocks (docs/perf/2026-12-04-gpu-h200.md).
            const auto warmUntil =
                std::chrono::steady_clock::now() + std::chrono::milliseconds(firstView ? 500 : 300);
            firstView = false;
            // Each setting's method and coarse pass, the instrumented variant or not.
            const auto use = [&](const Setting& setting, bool countFetches) {
                renderer.setMethod(setting.method, countFetches);
                renderer.setCoarsePass(setting.coarseTile);
            };
            for (const auto& [method, setting] : settings) {
                use(setting, false);
                draw();
                draw();
            }
            while (std::chrono::steady_clock::now() < warmUntil) {
                for (const auto& [method, setting] : settings) {
                    use(setting, false);
                    draw();
                    gl.Finish();
                }
            }
            for (const std::size_t k : interleavedOrder(settings.size(), options.frames)) {
                use(settings[k].second, false);
                const FrameTimes t = timer.frame(draw);
                rows[k].gpuFrames.push_back(t.gpu);
                rows[k].wallFrames.push_back(t.wall);
                rows[k].cpuFrames.push_back(t.cpu);
            }

            for (std::size_t k = 0; k < settings.size(); ++k) {
                const auto& [method, setting] = settings[k];
                Measurement& r = rows[k];
                r.method = methodName(method);
                r.param = setting.param;
                r.map = m.name;
                r.base = baseName(m.base);
                r.interpolation = interpolationName(m.interpolation);
                r.hitPct = 100.0 * referenceHits / reference.hits.size();
                const MethodCost& cost = costs.at(method);
                r.bytesPerTexel = cost.bytesPerTexel;
                r.preprocessMs = cost.preprocessMs;
                r.preprocessWhere = cost.where;
                r.cpuPreprocessMs = cost.cpuPreprocessMs;
                r.mapSize = mapSize;
                r.viewDegrees = degrees;
                r.width = options.width;
                r.height = options.height;
                r.msMedian = median(r.gpuFrames);
                r.msWallMedian = median(r.wallFrames);
                r.msCpuMedian = median(r.cpuFrames);

                // Accuracy from the plain variant's AOV: over every pixel, and over
                // those whose rays come in through the top face.
                use(setting, false);
                draw();
                const RenderedFrame frame = target.read(camera.eye);
                const Accuracy accuracy = compareWithReference(frame, camera, reference);
                r.coverageMismatchPct = accuracy.coverageMismatchPercent();
                r.offHalfTexelPct = accuracy.offHalfTexelPercent();
                r.meanErrorPx = accuracy.meanErrorPixels;
                r.p99ErrorPx = accuracy.p99ErrorPixels;
                r.p99ErrorTexels = accuracy.p99ErrorTexels;
                r.exhausted = accuracy.exhausted;
                const Accuracy top =
                    compareWithReference(frame, camera, reference, AccuracyScope::TopSurface);
                r.topCoverageMismatchPct = top.coverageMismatchPercent();
                r.topOffHalfTexelPct = top.offHalfTexelPercent();
                r.topP99ErrorTexels = top.p99ErrorTexels;

                // Fetches: the instrumented variant, once.
                use(setting, true);
                draw();
                const RenderedFrame counted = target.read(camera.eye);
                const double passReads = coarsePassReads(gl, renderer);
                double sum = 0.0, boundSum = 0.0;
                std::size_t covered = 0;
                for (std::size_t p = 0; p < inBox.size(); ++p) {
                    if (!inBox[p]) continue;
                    const double fetches = counted.stats[p * 4 + 1];
                    sum += fetches;
                    boundSum += counted.stats[p * 4 + 2];
                    ++covered;
                    r.fetchesMax = std::max(r.fetchesMax, fetches);
                }
                // The coarse pass's reads are the pixels' too: they are counted over the
                // same pixels, as bounds (the window pyramid's).
                r.coarseFetchesMean = covered ? passReads / covered : 0.0;
                r.fetchesMean = covered ? (sum + passReads) / covered : 0.0;
                r.boundFetchesMean = covered ? (boundSum + passReads) / covered : 0.0;
                report(r);
            }
            renderer.setCoarsePass(0);
        }
    }
}

}  // namespace microrelief::bench
