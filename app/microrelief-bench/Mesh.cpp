#include "Mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "Benchmark.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/base/BaseMeshes.h"
#include "microrelief/core/base/ReliefExtent.h"
#include "microrelief/core/trace/MeshTracer.h"
#include "microrelief/core/trace/MultilevelTracer.h"
#include "microrelief/gl/MeshRelief.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief::bench {

namespace {

// The height scale of every row: 0.1 of a map unit's height on the plane (world units) and
// of the radius on the cylinder (BaseShape.h), as the methods' run has it.
constexpr double kHeightScale = 0.1;

// The benchmark's relief with its last column and row copies of its first. The analytic
// bases clamp the map at an edge they do not wrap (the plane's four, the cylinder's top and
// bottom) and a mesh repeats it: within half a texel of such an edge the plane's surface is
// the edge sample and the mesh's runs towards the opposite edge's, different surfaces
// (0.3 % of the pixels hit by one only, up to 3 texels apart, at 45 degrees on 96 x 96).
// Seamless, the two are one surface, so that any difference left is a tracer's.
HeightMap seamlessRelief(int n) {
    HeightMap map = benchRelief(n);
    for (int j = 0; j < map.height; ++j) map.at(map.width - 1, j) = map.at(0, j);
    for (int i = 0; i < map.width; ++i) map.at(i, map.height - 1) = map.at(i, 0);
    return map;
}

// One mesh copying the analytic base, drawn by the GPU and traced by the CPU twin.
struct MeshCase {
    std::string name;
    TriangleMesh mesh;
    double heightScale = 0.0;  // s in the mesh's (the world's) units
    std::unique_ptr<gl::MeshRelief> relief;
};

// The analytic base's texel in world units: the square root of its side's area over the
// map's texel count (the plane's 1 / N; on the cylinder's side 2 pi R L over N^2).
double texelSize(const BaseShape& base, int mapSize) {
    const double texels = static_cast<double>(mapSize) * mapSize;
    if (!base.curved()) return 1.0 / mapSize;
    return std::sqrt(2.0 * std::numbers::pi * base.radius * base.length / texels);
}

std::vector<MeshCase> meshesFor(const GL& gl, const BaseShape& base, const HeightMap& map,
                                const MeshBenchOptions& options) {
    std::vector<MeshCase> cases;
    if (!base.curved()) {
        // The plane of a square map is [-1/2, 1/2]^2 (its longer side one unit).
        for (int n : options.gridQuads)
            cases.push_back({"grid " + std::to_string(n) + "x" + std::to_string(n),
                             planeGridMesh(n, 1.0f, 1.0f), kHeightScale, nullptr});
    } else {
        // On the cylinder s is a fraction of the radius: the world's s R.
        for (int sides : options.tubeSides) {
            const int rings = std::max(1, sides / 4);
            cases.push_back({"tube " + std::to_string(sides) + "x" + std::to_string(rings),
                             cylinderTubeMesh(sides, rings, static_cast<float>(base.radius),
                                              static_cast<float>(base.length)),
                             kHeightScale * base.radius, nullptr});
        }
    }
    for (MeshCase& c : cases)
        c.relief = std::make_unique<gl::MeshRelief>(gl, shaderDirectory(), c.mesh, map,
                                                    c.heightScale);
    return cases;
}

double frameMsOn(const FrameTimes& t, Clock clock) {
    return clock == Clock::Cpu ? t.cpu : clock == Clock::Wall ? t.wall : t.gpu;
}

// The two pictures' agreement: pixels hit by one only, and the common hits' distance.
void compare(const RenderedFrame& base, const RenderedFrame& mesh, double texel,
             MeshBenchRow& row) {
    std::vector<double> offsets;
    for (int r = 0; r < base.height; ++r) {
        for (int c = 0; c < base.width; ++c) {
            const bool a = base.positionAt(c, r)[3] > 0.5f, b = mesh.positionAt(c, r)[3] > 0.5f;
            ++row.pixels;
            row.baseHits += a;
            if (a != b) ++row.hitMiss;
            if (!a || !b) continue;
            offsets.push_back(
                glm::length(base.worldPositionAt(c, r) - mesh.worldPositionAt(c, r)) / texel);
        }
    }
    row.offsetMedian = median(offsets);
    row.offsetMax = offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end());
}

// Texels read per pixel by the CPU twins on every `stride`-th pixel's ray: the base's
// MultilevelTracer, and on the mesh every prism whose box the ray crosses (each of them
// gets a fragment on the GPU, which traces to its prism's first hit or exit).
void countFetches(const CameraFrame& camera, const MultilevelTracer& base, const MeshTracer& mesh,
                  int stride, MeshBenchRow& row) {
    double baseFetches = 0.0, meshFetches = 0.0, prisms = 0.0;
    int pixels = 0;
    for (int r = stride / 2; r < camera.height; r += stride) {
        for (int c = stride / 2; c < camera.width; c += stride) {
            const Ray ray = camera.pixelRay(c, r);
            TraversalStats stats;
            base.intersect(ray, &stats);
            baseFetches += stats.fetches;
            MeshTraceStats all;
            for (std::size_t k = 0; k < mesh.triangleCount(); ++k) {
                const glm::dvec2 span = mesh.boxSpan(ray, k);
                if (span.y >= 0.0 && span.x <= span.y) mesh.traceTriangle(ray, k, span.y, all);
            }
            meshFetches += all.fetches;
            prisms += all.triangles;
            ++pixels;
        }
    }
    row.twinPixels = pixels;
    row.baseFetches = pixels ? baseFetches / pixels : 0.0;
    row.meshFetches = pixels ? meshFetches / pixels : 0.0;
    row.prisms = pixels ? prisms / pixels : 0.0;
}

}  // namespace

void runMeshBench(GlContext& context, const MeshBenchOptions& options, Clock clock,
                  const std::function<void(const MeshBenchRow&)>& report) {
    context.makeCurrent();
    const GL& gl = context.gl();
    const HeightMap map = seamlessRelief(options.mapSize);
    ReliefRenderer renderer(gl, shaderDirectory());
    OffscreenTarget target(gl, options.width, options.height);
    Timer timer(gl);
    const ShadingOptions shading;

    for (const BaseShape& base : {BaseShape::plane(), BaseShape::cylinder()}) {
        const std::string baseName = base.curved() ? "cylinder" : "plane";
        if ((base.curved() ? options.tubeSides : options.gridQuads).empty()) continue;
        ReliefDesc relief;
        relief.base = base;
        relief.heightScale = static_cast<float>(kHeightScale);
        renderer.apply(relief, &map, "relief");
        std::vector<MeshCase> meshes = meshesFor(gl, base, map, options);
        const MultilevelTracer baseTwin(map, kHeightScale, base);
        const ReliefExtent extent = reliefExtent(map, kHeightScale, base);

        for (int degrees : options.viewDegrees) {
            const CameraFrame camera =
                resolveCamera(viewCamera(degrees, base, extent.topHeight), options.width,
                              options.height, sceneRadius(extent));
            // Setting 0 the base, k > 0 the mesh k - 1.
            const auto draw = [&](std::size_t setting) {
                target.clear(glm::vec3(0.0f));
                if (setting == 0)
                    renderer.draw(camera, shading);
                else
                    meshes[setting - 1].relief->draw(glm::mat4(camera.viewProjection),
                                                     camera.eye);
            };
            const std::size_t settings = meshes.size() + 1;
            // Each drawn twice (llvmpipe's variant of its program made), then all in turn
            // for 300 ms: the frames right after start-up and after the twins' CPU work run
            // slow on llvmpipe (Benchmark.cpp says what was measured).
            for (std::size_t k = 0; k < settings; ++k) {
                draw(k);
                draw(k);
            }
            const auto warmUntil = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
            while (std::chrono::steady_clock::now() < warmUntil)
                for (std::size_t k = 0; k < settings; ++k) draw(k);
            std::vector<std::vector<double>> series(settings);
            for (std::size_t k : interleavedOrder(settings, options.frames))
                series[k].push_back(frameMsOn(timer.frame([&] { draw(k); }), clock));

            draw(0);
            const RenderedFrame basePicture = target.read(camera.eye);
            for (std::size_t m = 0; m < meshes.size(); ++m) {
                MeshBenchRow row;
                row.base = baseName;
                row.degrees = degrees;
                row.mesh = meshes[m].name;
                row.triangles = static_cast<int>(meshes[m].mesh.triangleCount());
                row.proxyTriangles = meshes[m].relief->proxyTriangles();
                row.baseMs = median(series[0]);
                row.meshMs = median(series[m + 1]);
                row.ratio = pairedRatio(series[m + 1], series[0]);
                draw(m + 1);
                compare(basePicture, target.read(camera.eye), texelSize(base, options.mapSize),
                        row);
                const MeshTracer meshTwin(meshes[m].mesh, map, meshes[m].heightScale);
                countFetches(camera, baseTwin, meshTwin, options.twinStride, row);
                report(row);
            }
        }
    }
}

void writeMeshCsv(const std::filesystem::path& file, const std::string& renderer, Clock clock,
                  const std::vector<MeshBenchRow>& rows) {
    std::ostringstream out;
    out << "base,view_degrees,mesh,triangles,proxy_triangles,base_ms,mesh_ms,mesh_over_base,"
           "mesh_over_base_q1,mesh_over_base_q3,pixels,base_hits,hit_miss,offset_median_texels,"
           "offset_max_texels,base_fetches_per_pixel,mesh_fetches_per_pixel,prisms_per_pixel,"
           "twin_pixels,clock,renderer\n";
    for (const MeshBenchRow& r : rows) {
        out << r.base << ',' << r.degrees << ',' << r.mesh << ',' << r.triangles << ','
            << r.proxyTriangles << ',' << fixed(r.baseMs, 3) << ',' << fixed(r.meshMs, 3) << ','
            << fixed(r.ratio.median, 3) << ',' << fixed(r.ratio.low, 3) << ','
            << fixed(r.ratio.high, 3) << ',' << r.pixels << ',' << r.baseHits << ',' << r.hitMiss
            << ',' << fixed(r.offsetMedian, 4) << ',' << fixed(r.offsetMax, 4) << ','
            << fixed(r.baseFetches, 2) << ',' << fixed(r.meshFetches, 2) << ','
            << fixed(r.prisms, 2) << ',' << r.twinPixels << ',' << clockName(clock) << ','
            << csvQuote(renderer) << '\n';
    }
    writeTextAtomically(file, out.str());
}

std::string meshTable(const std::string& renderer, Clock clock, const std::string& date,
                      const MeshBenchOptions& options, const std::vector<MeshBenchRow>& rows) {
    std::ostringstream md;
    md << "Mesh run " << date << " on " << renderer << ": the benchmark's relief at "
       << options.mapSize << " x " << options.mapSize << ", " << options.width << " x "
       << options.height << " pixels, " << options.frames << " rounds, medians on the "
       << clockName(clock)
       << " clock; mesh / base paired by round (quartiles); fetches per pixel by the CPU twins "
          "on every "
       << options.twinStride << "th pixel each way (the mesh: every prism whose box the ray "
                                "crosses). The map is made seamless and laid at height "
                                "scale 0.1 (the cylinder's: 0.1 of its radius), the cameras "
                                "the methods run's (viewCamera). A flat grid is the plane: "
                                "its pictures must agree on every pixel; a tube differs from "
                                "the cylinder where its chords do (silhouettes, the caps). "
                                "Target (issue 50): mesh / plane <= 2 up to 10k triangles.\n\n"
       << "| base | view | mesh | triangles (proxy) | base ms | mesh ms | mesh / base | "
          "hit/miss differ | offset median (max), texels | fetches base | fetches mesh | "
          "prisms a pixel |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const MeshBenchRow& r : rows) {
        md << "| " << r.base << " | " << r.degrees << " | " << r.mesh << " | " << r.triangles
           << " (" << r.proxyTriangles << ") | " << fixed(r.baseMs, 2) << " | "
           << fixed(r.meshMs, 2) << " | " << fixed(r.ratio.median, 2) << " ("
           << fixed(r.ratio.low, 2) << "-" << fixed(r.ratio.high, 2) << ") | "
           << fixed(r.pixels ? 100.0 * r.hitMiss / r.pixels : 0.0, 2) << " % | "
           << fixed(r.offsetMedian, 3) << " (" << fixed(r.offsetMax, 2) << ") | "
           << fixed(r.baseFetches, 1) << " | " << fixed(r.meshFetches, 1) << " | "
           << fixed(r.prisms, 1) << " |\n";
    }
    return md.str();
}

}  // namespace microrelief::bench
