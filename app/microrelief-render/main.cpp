// microrelief-render: the headless screenshot program. Thin wiring: parse, load the
// map, render in an offscreen framebuffer, write the picture and the AOV atomically;
// or, given a camera path, hand over to runBatch.
// On failure: one line on stderr and exit status 2 (bad arguments or input) or 1.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include "Aov.h"
#include "BatchRender.h"
#include "EyeInside.h"
#include "MeshNotes.h"
#include "Options.h"
#include "Progress.h"
#include "PyramidCache.h"
#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/core/trace/ReferenceTracer.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/io/MeshFile.h"
#include "microrelief/io/PyramidFile.h"
#include "microrelief/io/ReliefFiles.h"

using namespace microrelief;

namespace {

constexpr const char* kProgram = "microrelief-render";

// --compare-reference: the accuracy sweep's figures for this one view.
// A tiled map is compared with its larger image, made by repeating it.
// The lines of --compare-reference; `sampled`: the reference traced some pixels only.
void printAccuracy(const Accuracy& a, bool sampled) {
    std::printf(
        "accuracy against the exact CPU reference (%zu %spixels, %zu hit in the reference):\n",
        a.pixels, sampled ? "sampled " : "", a.referenceHits);
    std::printf("  hit/miss disagreement        %8zu px  %8.4f %% of pixels\n",
                a.coverageMismatches, a.coverageMismatchPercent());
    std::printf("  off by more than half a texel %7zu px  %8.4f %% of hit pixels\n", a.offHalfTexel,
                a.offHalfTexelPercent());
    std::printf("  position error               p99 %.3g texels, max %.3g texels\n",
                a.p99ErrorTexels, a.maxErrorTexels);
    std::printf("                               mean %.3g px, p99 %.3g px (pixels at the hit)\n",
                a.meanErrorPixels, a.p99ErrorPixels);
    std::printf("  out of the iteration budget  %8zu px\n", a.exhausted);
}

// --compare-reference over a map in memory: every pixel.
void printAccuracy(const RenderedFrame& frame, const CameraFrame& camera, const HeightMap& map,
                   const RenderJob& job) {
    const bool tiled = job.tiles != glm::ivec2(1, 1);
    const HeightMap whole = tiled ? repeatMap(map, job.tiles.x, job.tiles.y) : HeightMap();
    printAccuracy(compareWithReference(frame, camera,
                                       ReliefGeometry{tiled ? &whole : &map, job.heightScale,
                                                      job.base, job.interpolation, job.model}),
                  false);
}

// ", paged: 12 draws, 340 pages loaded" for a map read through pages; "" otherwise.
std::string pagingSummary(const PagingReport& paging) {
    if (paging.draws == 0) return "";
    return ", paged: " + std::to_string(paging.draws) + " draws, " +
           std::to_string(paging.pagesLoaded) + " pages loaded";
}

// The GL context of --backend, named with -v.
std::unique_ptr<GlContext> openContext(const RenderOptions& o) {
    auto context = createHeadlessContext(o.backend);
    if (o.verbose)
        logInfo("GL: " + context->renderer() + ", " + context->version() + " via " +
                context->description());
    return context;
}

// What run() drew, and of what map.
struct Drawn {
    HeadlessResult result;
    std::string context;  // the GL's description
    glm::ivec2 mapSize{0};
};

// The job over a W x H map: a georeferenced map's true proportions where the flags leave
// them to it, and a line saying what its grid gave (or that --exaggeration has nothing to
// scale).
RenderJob jobOverMap(const RenderOptions& o, const std::filesystem::path& heightFile, int width,
                     int height, const std::optional<Georeference>& georeference) {
    const std::string name = heightFile.string();
    const RenderJob job =
        sceneOverMap(o.scene.job, o.scene.georeference, width, height, georeference, name);
    if (const std::string unused = exaggerationUnused(name, o.scene.georeference, georeference);
        !unused.empty())
        logWarning(unused);
    if (georeference && !o.quiet)
        std::printf("%s: %s\n", kProgram,
                    georeferenceSummary(name, *georeference, job, o.scene.georeference).c_str());
    return job;
}

// --pyramid-cache: the map's pyramid file, built where missing or stale, drawn through pages;
// the map itself is never read whole (no --compare-reference, no check of the eye).
Drawn drawFromPyramidFile(const RenderOptions& o, const std::filesystem::path& heightFile) {
    // The job on the base it is drawn on (a global grid's ellipsoid), checked before a build.
    RenderJob asked = o.scene.job;
    asked.base = drawnBase(o.scene, heightFile);
    checkDrawnFromPyramidFile(asked, o.compareReference);
    const std::string name = heightFile.string();
    const std::shared_ptr<const PyramidFile> pages =
        openPyramidCache(o, heightFile, asked.map.load, asked.base.wrapsU());
    const RenderJob job =
        jobOverMap(o, heightFile, pages->mapWidth(), pages->mapHeight(), pages->georeference());
    const ReliefFiles colours = loadReliefFiles(job, ReliefParts::Albedo);
    const auto context = openContext(o);
    Drawn drawn;
    {
        HeadlessRenderer renderer(*context, job.method);  // its GL objects die before the context
        renderer.setPaging(o.paging);
        renderer.setPyramidPages(pages, name, job.base, job.interpolation);
        if (colours.albedo) renderer.setAlbedo(&*colours.albedo, colours.albedoFile->string());
        drawn.result = renderer.render(job);
    }
    drawn.context = context->description();
    drawn.mapSize = {pages->mapWidth(), pages->mapHeight()};
    if (o.compareReference) {
        // The map is not in memory: the reference reads its samples from the file, on
        // sampled pixels.
        const PagedReferenceTracer reference(pages, job.heightScale, job.interpolation, job.model);
        const CameraFrame& camera = drawn.result.camera;
        const ReferencePicture exact = traceSampledReferencePicture(
            camera, [&](const Ray& ray) { return reference.trace(ray); },
            1.0 / job.base.texelSize(pages->mapWidth(), pages->mapHeight()),
            glm::dmat3(job.model.worldToObject()));
        printAccuracy(compareWithReference(drawn.result.frame, camera, exact), true);
    }
    return drawn;
}

// The map loaded whole and drawn (through pages where it is larger than the GL's textures).
Drawn drawLoadedMap(const RenderOptions& o, const std::filesystem::path& heightFile) {
    // The map and its colours, as the description names them (io/ReliefFiles.h). The map is
    // shared with the renderer: one read through pages is kept by its pages, not copied.
    const ReliefFiles files = loadFilesOrPointToCache(o.scene.job, o.compareReference);
    const std::shared_ptr<const HeightMap>& shared = files.heights;
    const HeightMap& map = *shared;
    const RenderJob job = jobOverMap(o, heightFile, map.width, map.height, files.georeference);
    if (o.compareReference && job.tiles != glm::ivec2(1, 1) &&
        map.samples.size() * job.tiles.x * job.tiles.y > (std::size_t(1) << 26)) {
        throwBadInput(
            "--compare-reference with " + flagName("tiles") +
            " compares with the larger image the tiles make, at most 67108864 samples (this "
            "one would have " +
            std::to_string(map.samples.size() * job.tiles.x * job.tiles.y) + ")");
    }
    const auto context = openContext(o);
    Drawn drawn;
    drawn.result = renderHeadless(*context, shared, heightFile.string(), job,
                                  files.albedo ? &*files.albedo : nullptr, o.paging);
    drawn.context = context->description();
    drawn.mapSize = {map.width, map.height};
    // An animated relief is held to the heights the GPU evaluated, read back.
    const HeightMap& traced = drawn.result.animatedMap ? *drawn.result.animatedMap : map;
    if (eyeInsideTheSolid(traced, job)) {  // the camera checked by now
        logWarning(flagName("camera.eye") +
                   " lies inside the relief's solid (under the surface of " +
                   heightFile.filename().string() +
                   "): the picture is undefined there; move the eye above the surface");
    }
    if (o.compareReference) printAccuracy(drawn.result.frame, drawn.result.camera, traced, job);
    return drawn;
}

// The mesh base (--base mesh --mesh FILE): the map and the mesh read whole (io/ReliefFiles.h),
// the camera framing the mesh's shell where the command line gives no eye or target
// (meshCamera), drawn by gl::MeshRelief (gl/HeadlessRender.h). No georeference fit: the
// mesh's units are its file's.
Drawn drawMesh(const RenderOptions& o) {
    const ReliefFiles files = loadReliefFiles(o.scene.job, ReliefParts::Heights);
    const std::string name = files.meshFile ? files.meshFile->string() : std::string("the mesh");
    RenderJob job = o.scene.job;
    const TriangleMesh& mesh = *files.mesh;
    const double top = files.heights->maxValue();
    // Before the camera frames it (HeadlessRenderer::render checks it again).
    checkMeshFloatLimits(mesh, *files.heights, job.heightScale, name);
    const ReliefExtent shell = meshShellExtent(mesh, job.heightScale, top);
    // What --height-scale is measured against: it is in the mesh's units.
    if (o.verbose) logInfo(meshSizeLine(name, mesh, job.heightScale, top));
    job.camera = meshCamera(job.camera, o.eyeGiven, o.targetGiven, shell, job.width, job.height);
    if (o.verbose && !(o.eyeGiven && o.targetGiven))
        logInfo("the camera framing the mesh: " + flagName("camera.eye") + "=" +
                exactVector(job.camera.eye) + " " + flagName("camera.target") + "=" +
                exactVector(job.camera.target));
    const auto context = openContext(o);
    Drawn drawn;
    {
        HeadlessRenderer renderer(*context, job.method);  // its GL objects die before the context
        renderer.setMesh(files.mesh, files.heights, name);
        drawn.result = renderer.render(job);
    }
    // Warnings once the picture is drawn (a refusal is one line alone).
    warnOfZeroUvArea(name, mesh);
    // The mesh's classes take the map's rows reversed (HeightMap.h: rowsReversed).
    if (eyeInsideTheMeshSolid(mesh, rowsReversed(*files.heights), job)) {  // checked by now
        logWarning(flagName("camera.eye") + " lies inside the relief's solid on " +
                   std::filesystem::path(name).filename().string() +
                   " (in the shell between the mesh and the relief's top, as the exact "
                   "reference traces it): the picture is undefined there; move the eye out "
                   "of the shell");
    }
    drawn.context = context->description();
    drawn.mapSize = {files.heights->width, files.heights->height};
    return drawn;
}

int run(const RenderOptions& o) {
    if (o.batch.active()) return runBatch(o);  // a camera path: many frames
    const auto start = std::chrono::steady_clock::now();
    if (o.aov) checkAovExtension(*o.aov);
    checkOutputTargets(o.aov ? std::vector<std::filesystem::path>{o.out, *o.aov}
                             : std::vector{o.out});
    // Neither output may be a file the picture is drawn from (the map, its albedo).
    std::vector<NamedFile> outputs{{o.out, "--out"}};
    if (o.aov) outputs.push_back({*o.aov, "--aov"});
    checkOutputsAreNotInputs(outputs, filesRead(o.scene.job));
    if (o.lightSizeGiven && o.scene.job.shading.shadows != ShadowMode::Soft)
        logWarning(lightSizeUnused());
    const std::filesystem::path heightFile = heightMapPath(o.scene.job);
    const Drawn drawn = o.scene.job.onMesh ? drawMesh(o)
                        : o.pyramidCache   ? drawFromPyramidFile(o, heightFile)
                                           : drawLoadedMap(o, heightFile);
    const RenderedFrame& frame = drawn.result.frame;

    std::size_t exhausted = 0;
    for (std::size_t p = 3; p < frame.stats.size(); p += 4) exhausted += frame.stats[p] > 0.0f;

    ImageWriteBatch batch;
    const std::vector<std::uint8_t> rgb = rgbFromRgba(frame.color, frame.width, frame.height);
    batch.write(o.out, {frame.width, frame.height, 3, PixelType::UInt8, rgb.data(), {}});
    if (o.aov) writeAov(batch, *o.aov, frame, o.scene.job.shading.shadows != ShadowMode::Off);
    batch.commit();

    if (exhausted > 0) {
        logWarning(std::to_string(exhausted) +
                   " pixel(s) ran out of the iteration budget (shown magenta)");
    }
    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%s: wrote %s%s%s (%dx%d, map %dx%d%s, %.2f s, %s)\n", kProgram, o.out.c_str(),
                    o.aov ? " and " : "", o.aov ? o.aov->c_str() : "", frame.width, frame.height,
                    drawn.mapSize.x, drawn.mapSize.y, pagingSummary(drawn.result.paging).c_str(),
                    seconds, drawn.context.c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return runProgram<RenderOptions>(kProgram, parseRenderOptions(argc, argv), run);
}
