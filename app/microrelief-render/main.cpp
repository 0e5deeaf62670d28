// microrelief-render: the headless screenshot program. Thin wiring: parse, load the
// map, render in an offscreen framebuffer, write the picture and the AOV atomically;
// or, given a camera path, hand over to runBatch.
// On failure: one line on stderr and exit status 2 (bad arguments or input) or 1.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "Aov.h"
#include "BatchRender.h"
#include "EyeInside.h"
#include "Options.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/AlbedoFile.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/core/trace/Accuracy.h"
#include "microrelief/core/trace/ReferenceTracer.h"

using namespace microrelief;

namespace {

constexpr const char* kProgram = "microrelief-render";

// --compare-reference: the accuracy sweep's figures for this one view.
// A tiled map is compared with its larger image, made by repeating it.
void printAccuracy(const RenderedFrame& frame, const CameraFrame& camera, const HeightMap& map,
                   const RenderJob& job) {
    const bool tiled = job.tiles != glm::ivec2(1, 1);
    const HeightMap whole = tiled ? repeatMap(map, job.tiles.x, job.tiles.y) : HeightMap();
    const Accuracy a = compareWithReference(frame, camera,
                                            ReliefGeometry{tiled ? &whole : &map, job.heightScale,
                                                           job.base, job.interpolation, job.model});
    std::printf(
        "accuracy against the exact CPU reference (%zu pixels, %zu hit in the reference):\n",
        a.pixels, a.referenceHits);
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

// ", paged: 12 draws, 340 pages loaded" for a map read through pages; "" otherwise.
std::string pagingSummary(const PagingReport& paging) {
    if (paging.draws == 0) return "";
    return ", paged: " + std::to_string(paging.draws) + " draws, " +
           std::to_string(paging.pagesLoaded) + " pages loaded";
}

int run(const RenderOptions& o) {
    if (o.batch.active()) return runBatch(o);  // a camera path: many frames
    const auto start = std::chrono::steady_clock::now();
    if (o.aov && o.aov->extension() != ".exr") {
        throwBadInput(o.aov->string() + ": the AOV must be an OpenEXR file (.exr)");
    }
    checkOutputTargets(o.aov ? std::vector<std::filesystem::path>{o.out, *o.aov}
                             : std::vector{o.out});
    if (o.lightSizeGiven && o.scene.job.shading.shadows != ShadowMode::Soft)
        logWarning(kLightSizeUnused);
    const std::filesystem::path heightFile =
        o.scene.job.map.file ? *o.scene.job.map.file : defaultHeightMapPath();
    const HeightMapFile loaded = loadHeightMapFile(heightFile, o.scene.job.map.load);
    const HeightMap& map = loaded.map;
    // A georeferenced map's true proportions, where the flags leave them to it.
    const RenderJob job = sceneOverMap(o.scene.job, o.scene.georeference, map.width, map.height,
                                       loaded.georeference, heightFile.string());
    if (const std::string unused =
            exaggerationUnused(heightFile.string(), o.scene.georeference, loaded.georeference);
        !unused.empty())
        logWarning(unused);
    if (loaded.georeference && !o.quiet)
        std::printf("%s: %s\n", kProgram,
                    georeferenceSummary(heightFile.string(), *loaded.georeference, job,
                                        o.scene.georeference)
                        .c_str());
    if (o.compareReference && job.tiles != glm::ivec2(1, 1) &&
        map.samples.size() * job.tiles.x * job.tiles.y > (std::size_t(1) << 26)) {
        throwBadInput(
            "--compare-reference with --tile compares with the larger image the tiles "
            "make, at most 67108864 samples (this one would have " +
            std::to_string(map.samples.size() * job.tiles.x * job.tiles.y) + ")");
    }
    const std::optional<std::filesystem::path> albedoFile = albedoPath(job);
    const std::optional<AlbedoImage> albedo =
        albedoFile ? std::optional<AlbedoImage>(loadAlbedo(*albedoFile)) : std::nullopt;

    const auto context = createHeadlessContext(o.backend);
    if (o.verbose)
        logInfo("GL: " + context->renderer() + ", " + context->version() + " via " +
                context->description());
    const HeadlessResult result = renderHeadless(*context, map, heightFile.string(), job,
                                                 albedo ? &*albedo : nullptr, o.paging);
    // An animated relief is held to the heights the GPU evaluated, read back.
    const HeightMap& traced = result.animatedMap ? *result.animatedMap : map;
    if (eyeInsideTheSolid(traced, job)) {  // the camera checked by now
        logWarning("--eye lies inside the relief's solid (under the surface of " +
                   heightFile.filename().string() +
                   "): the picture is undefined there; move the eye above the surface");
    }
    const RenderedFrame& frame = result.frame;

    std::size_t exhausted = 0;
    for (std::size_t p = 3; p < frame.stats.size(); p += 4) exhausted += frame.stats[p] > 0.0f;

    ImageWriteBatch batch;
    const std::vector<std::uint8_t> rgb = rgbFromRgba(frame.color, frame.width, frame.height);
    batch.write(o.out, {frame.width, frame.height, 3, PixelType::UInt8, rgb.data(), {}});
    if (o.aov) writeAov(batch, *o.aov, frame, job.shading.shadows != ShadowMode::Off);
    batch.commit();

    if (o.compareReference) printAccuracy(frame, result.camera, traced, job);
    if (exhausted > 0) {
        logWarning(std::to_string(exhausted) +
                   " pixel(s) ran out of the iteration budget (shown magenta)");
    }
    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%s: wrote %s%s%s (%dx%d, map %dx%d%s, %.2f s, %s)\n", kProgram, o.out.c_str(),
                    o.aov ? " and " : "", o.aov ? o.aov->c_str() : "", frame.width, frame.height,
                    map.width, map.height, pagingSummary(result.paging).c_str(), seconds,
                    context->description().c_str());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return runProgram<RenderOptions>(kProgram, parseRenderOptions(argc, argv), run);
}
