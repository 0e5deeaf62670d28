// Materials (issue 14): the albedo's level of detail at grazing angles against a
// supersampled picture of the same view.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/core/image/Albedo.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

class Materials : public test::GlTest {};

// A black and white checker of `square`-texel squares, linear float.
AlbedoImage checker(int side, int square) {
    AlbedoImage image;
    image.width = image.height = side;
    image.linear.resize(static_cast<std::size_t>(side) * side * 4);
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
            const float value = ((i / square + j / square) % 2) ? 0.9f : 0.05f;
            float* p = &image.linear[(static_cast<std::size_t>(j) * side + i) * 4];
            p[0] = p[1] = p[2] = value;
            p[3] = 1.0f;
        }
    }
    return image;
}

// The picture's colour as linear values, one per channel, and whether each pixel hit.
struct LinearPicture {
    int width = 0, height = 0;
    std::vector<double> rgb;
    std::vector<bool> hit;
};

LinearPicture linearPicture(const RenderedFrame& frame) {
    LinearPicture p{frame.width, frame.height, {}, {}};
    for (std::size_t k = 0; k < frame.color.size(); k += 4) {
        for (int c = 0; c < 3; ++c) p.rgb.push_back(srgbToLinear(frame.color[k + c] / 255.0f));
        p.hit.push_back(frame.position[k + 3] > 0.5f);
    }
    return p;
}

// Box-filtered by `factor` x `factor` blocks: a pixel of the result is the mean of the
// rays through its factor^2 sub-pixel centres; a block counts as hit when all its rays do.
LinearPicture boxFiltered(const LinearPicture& fine, int factor) {
    LinearPicture p{fine.width / factor, fine.height / factor, {}, {}};
    for (int row = 0; row < p.height; ++row) {
        for (int column = 0; column < p.width; ++column) {
            double sum[3] = {0, 0, 0};
            bool all = true;
            for (int y = 0; y < factor; ++y) {
                for (int x = 0; x < factor; ++x) {
                    const std::size_t k = static_cast<std::size_t>(row * factor + y) * fine.width +
                                          column * factor + x;
                    for (int c = 0; c < 3; ++c) sum[c] += fine.rgb[3 * k + c];
                    all = all && fine.hit[k];
                }
            }
            for (int c = 0; c < 3; ++c) p.rgb.push_back(sum[c] / (factor * factor));
            p.hit.push_back(all);
        }
    }
    return p;
}

// Mean absolute difference over the pixels both hit, per channel.
double meanDifference(const LinearPicture& a, const LinearPicture& b, int& pixels) {
    double sum = 0.0;
    pixels = 0;
    for (std::size_t k = 0; k < a.hit.size(); ++k) {
        if (!a.hit[k] || !b.hit[k]) continue;
        ++pixels;
        for (int c = 0; c < 3; ++c) sum += std::abs(a.rgb[3 * k + c] - b.rgb[3 * k + c]);
    }
    return pixels ? sum / (3.0 * pixels) : 0.0;
}

// A fine checker (2-texel squares on a 1024 texture, 256 squares a map side, far finer
// than the pixels far off) on a flat map seen from just above it. The supersampled
// picture traces 16 rays a pixel (the same view at 4 x 4 times the pixels, the albedo's
// finest level at each ray) and box-filters them: what the pixel covers. The filtered
// picture (taps along the footprint from ray differentials) must be within 0.07 of it in
// the mean (linear units; the checker spans 0.05 to 0.9, so a pixel aliased to either
// colour is 0.4 off; measured 0.057: the trilinear taps' kernel is wider than a pixel's
// box, and 16 rays still alias where a square is under a quarter pixel), and at most 0.4
// times as far off as sampling the finest level with one ray a pixel, which aliases
// (measured 0.226). Half the footprint's size (a sharper level) gives 0.119, the GL's
// own anisotropic sampler on llvmpipe 0.075, plain trilinear 0.100.
TEST_F(Materials, AlbedoFilteredOverThePixelFootprintAtGrazingAngles) {
    const HeightMap map = synth::flat(64, 64, 0.1f);
    const AlbedoImage albedo = checker(1024, 2);
    RenderJob job;
    // Inside the map's footprint, 3 cm above its top, looking across it to the far corner:
    // every ray meets the top, at 2 to 30 degrees.
    job.camera.eye = {0.35, 0.04, 0.35};
    job.camera.target = {-0.4, 0.0, -0.3};
    job.camera.fovyDegrees = 40.0;
    job.shading.lightDirection = glm::vec3(0.0f, 1.0f, 0.0f);
    const int size = 96, factor = 4;
    auto render = [&](int side, bool finest) {
        RenderJob j = job;
        j.width = j.height = side;
        j.shading.albedoFinestLevel = finest;
        return linearPicture(renderHeadless(test::glContext(), map, "flat", j, &albedo).frame);
    };
    const LinearPicture filtered = render(size, false), finest = render(size, true);
    const LinearPicture reference = boxFiltered(render(size * factor, true), factor);
    int pixels = 0;
    const double filteredError = meanDifference(filtered, reference, pixels);
    const double finestError = meanDifference(finest, reference, pixels);
    std::printf(
        "    %d pixels: mean |filtered - supersampled| %.4f, |finest level - supersampled| "
        "%.4f\n",
        pixels, filteredError, finestError);
    EXPECT_GT(pixels, size * size / 4);
    EXPECT_LT(filteredError, 0.07);
    EXPECT_LT(filteredError, 0.4 * finestError);
}

}  // namespace

namespace {

// A map tiled N x M is the N x M larger image made by repeating it (issue 14): per pixel,
// the tiled picture's hits against the exact reference on the larger image, at the
// thresholds of every other view (hit/miss 0.1 % of pixels, off by more than half a
// texel 0.2 % of hits), and against the picture of the larger image uploaded whole
// (positions within 1e-4 world units: the same exact hits, by other float paths). The
// maps are odd, non-square and smaller than a power of two, so that the tiles' seams
// fall inside pyramid windows; the views take in whole rows of seams, on the plane with
// both last levels, round and along a cylinder and round a sphere.
TEST_F(Materials, TiledMapIsTheLargerImageMadeByRepeatingIt) {
    const HeightMap tile = synth::cobbles(23, 17, 41);
    struct Case {
        const char* name;
        BaseShape base;
        Interpolation interpolation;
        glm::ivec2 tiles;
        Camera camera;
    };
    const Case cases[] = {{"plane 3 x 2, bilinear",
                           {},
                           Interpolation::Bilinear,
                           {3, 2},
                           test::orbitCamera(40.0, 30.0, 1.4)},
                          {"plane 3 x 2, biquadratic",
                           {},
                           Interpolation::Biquadratic,
                           {3, 2},
                           test::orbitCamera(25.0, 70.0, 1.3)},
                          {"plane 5 x 4, grazing",
                           {},
                           Interpolation::Bilinear,
                           {5, 4},
                           test::orbitCamera(8.0, 10.0, 1.2)},
                          {"cylinder 3 x 2",
                           BaseShape::cylinder(0.3, 1.0),
                           Interpolation::Bilinear,
                           {3, 2},
                           test::orbitCamera(20.0, 30.0, 1.3)},
                          {"sphere 4 x 2, biquadratic",
                           BaseShape::sphere(0.5),
                           Interpolation::Biquadratic,
                           {4, 2},
                           test::orbitCamera(30.0, 200.0, 1.6)}};
    for (const Case& c : cases) {
        RenderJob job;
        job.width = job.height = 96;
        job.camera = c.camera;
        job.base = c.base;
        job.interpolation = c.interpolation;
        job.heightScale = 0.05f;
        RenderJob tiledJob = job;
        tiledJob.tiles = c.tiles;
        const HeightMap whole = repeatMap(tile, c.tiles.x, c.tiles.y);
        const HeadlessResult tiled = renderHeadless(test::glContext(), tile, "tile", tiledJob);
        const HeadlessResult single = renderHeadless(test::glContext(), whole, "whole", job);
        const test::Accuracy a = test::compareWithReference(
            tiled.frame, tiled.camera,
            ReliefGeometry{&whole, job.heightScale, c.base, c.interpolation});
        int both = 0, apart = 0, coverage = 0;
        for (std::size_t p = 0; p < tiled.frame.position.size(); p += 4) {
            const bool hitA = tiled.frame.position[p + 3] > 0.5f,
                       hitB = single.frame.position[p + 3] > 0.5f;
            coverage += hitA != hitB;
            if (!hitA || !hitB) continue;
            ++both;
            const glm::dvec3 d(tiled.frame.position[p] - single.frame.position[p],
                               tiled.frame.position[p + 1] - single.frame.position[p + 1],
                               tiled.frame.position[p + 2] - single.frame.position[p + 2]);
            apart += glm::length(d) > 1e-4;
        }
        std::printf("    %-28s %s; against the whole image: %d of %d hits apart, %d hit/miss\n",
                    c.name, a.summary().c_str(), apart, both, coverage);
        EXPECT_GT(a.referenceHits, 1500u) << c.name;
        EXPECT_LE(a.coverageMismatchPercent(), 0.1) << c.name;
        EXPECT_LE(a.offHalfTexelPercent(), 0.2) << c.name;
        EXPECT_EQ(a.exhausted, 0u) << c.name;
        EXPECT_LE(coverage * 1000, job.width * job.height) << c.name;
        EXPECT_LE(apart * 500, both) << c.name;
    }
}

}  // namespace
