// The coarse pass (ReliefRenderer::setCoarsePass, shaders/microrelief/coarse_start.glsl):
// the picture with it is the picture without it, and the start each tile's texel holds is
// never after the first hit of any of the tile's pixels, as the single pass finds them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/gl/OffscreenTarget.h"
#include "microrelief/gl/ReliefRenderer.h"
#include "microrelief/gl/ReliefShader.h"
#include "microrelief/gl/StateGuard.h"

using namespace microrelief;

namespace {

class CoarsePass : public test::GlTest {};

// The coarse texture's used texels, GL's order (row 0 at the bottom), RGBA each.
std::vector<float> readCoarse(const GL& gl, const ReliefRenderer& renderer) {
    const glm::ivec2 size = renderer.coarseStartSize();
    auto framebuffer = gl::Framebuffer::create(gl);
    const gl::PassGuard guard(gl);
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                            renderer.coarseStartTexture(), 0);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    std::vector<float> texels(4 * static_cast<std::size_t>(size.x) * size.y);
    gl.ReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_FLOAT, texels.data());
    return texels;
}

struct View {
    const char* name;
    Camera camera;
};

// Far and near, grazing, and an eye inside the relief's box (under the box's top,
// 0.1 x the map's highest sample).
std::vector<View> views() {
    return {{"45 deg far", test::orbitCamera(45.0, 30.0, 1.4)},
            {"70 deg near", test::orbitCamera(70.0, 110.0, 0.45, {0.1, 0.0, -0.05})},
            {"10 deg", test::orbitCamera(10.0, 200.0, 1.2, {0.0, 0.03, 0.0})},
            {"3 deg grazing", test::orbitCamera(3.0, 60.0, 0.9, {0.0, 0.05, 0.0})},
            {"eye inside the box", test::orbitCamera(20.0, 300.0, 0.2, {0.05, 0.02, 0.0})},
            {"eye in the solid", test::orbitCamera(4.0, 300.0, 0.35, {0.05, 0.06, 0.0})}};
}

// With the pass (8 x 8 tiles, and 4 x 4 on the bilinear surface), every pixel hits or misses as
// without it, at the same point to float rounding: positions (about the eye) within 2e-5 of the
// hit's distance, some 300 float ulps (the walk starts elsewhere, so its leaves solve from other
// points of the same ray: the roots agree, their rounding does not). And each tile's start is at
// most the single pass's hit distance of each of its pixels (t = |position| / |direction|), and a
// tile whose rays all miss holds only missing pixels. Fetches per pixel with and without (the
// instrumented variant; the pass's own reads per pixel besides) are printed, not asserted.
TEST_F(CoarsePass, PicturesAreTheSinglePassesAndTheStartNeverPassesAHit) {
    GlContext& context = test::glContext();
    context.makeCurrent();
    const GL& gl = context.gl();
    const HeightMap map = synth::cobbles(256, 256, 3);
    const int width = 96, height = 72;
    OffscreenTarget target(gl, width, height);
    ReliefRenderer renderer(gl, shaderDirectory());
    renderer.apply(test::relief({}, Interpolation::Bilinear, 0.1f), &map, "cobbles");
    EXPECT_THROW(renderer.setCoarsePass(1), Error);
    EXPECT_THROW(renderer.setCoarsePass(65), Error);
    for (const Interpolation interpolation :
         {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        renderer.apply(test::relief({}, interpolation, 0.1f), &map, "cobbles");
        for (const View& view : views()) {
            const CameraFrame camera = renderer.resolveCamera(view.camera, width, height);
            auto drawn = [&](int tile, bool countFetches) {
                renderer.setCoarsePass(tile);
                renderer.setMethod(MethodSettings{}, countFetches);
                target.clear(glm::vec3(0.0f));
                renderer.draw(camera, ShadingOptions{});
                EXPECT_EQ(renderer.coarsePassDrawn(), tile > 0);
                return target.read(camera.eye);
            };
            const RenderedFrame single = drawn(0, false);
            const RenderedFrame singleCounted = drawn(0, true);
            double singleFetches = 0.0;
            for (int i = 0; i < width * height; ++i)
                singleFetches += singleCounted.stats[4 * i + 1];
            std::size_t hits = 0;
            for (int i = 0; i < width * height; ++i) hits += single.position[4 * i + 3] != 0.0f;
            ASSERT_GT(hits, std::size_t(width * height / 10)) << view.name;
            // 4 x 4 on the bilinear surface only (the test's time on OSMesa).
            for (const int tile : {8, 4}) {
                if (tile == 4 && interpolation == Interpolation::Biquadratic) continue;
                const std::string what = std::string(interpolationName(interpolation)) + ", " +
                                         view.name + ", tile " + std::to_string(tile);
                const RenderedFrame coarse = drawn(tile, false);
                const std::vector<float> starts = readCoarse(gl, renderer);
                const glm::ivec2 size = renderer.coarseStartSize();
                ASSERT_EQ(size, glm::ivec2((width + tile - 1) / tile, (height + tile - 1) / tile));
                std::size_t sameKind = 0, close = 0, beforeHit = 0, missTiles = 0, movedTiles = 0;
                double worst = 0.0;
                for (int row = 0; row < height; ++row) {
                    for (int column = 0; column < width; ++column) {
                        const float* a = single.positionAt(column, row);
                        const float* b = coarse.positionAt(column, row);
                        sameKind += a[3] == b[3];
                        const glm::ivec2 texel(column / tile, (height - 1 - row) / tile);
                        const float start = starts[4 * (std::size_t(texel.y) * size.x + texel.x)];
                        const glm::dvec3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]);
                        if (a[3] == 0.0f) {
                            close += b[3] == 0.0f;
                            beforeHit += 1;
                            continue;
                        }
                        // An eye in the solid hits at 0: the same point, 0, is asked.
                        const double distance = glm::length(pa);
                        const double error = glm::length(pa - pb) / std::max(distance, 1e-30);
                        worst = std::max(worst, error);
                        close += b[3] != 0.0f && error <= 2e-5;
                        const double t =
                            distance / glm::length(camera.pixelRay(column, row).direction);
                        // The start is a distance, or -1 (keep the pixel's own), or 3.4e38
                        // (every ray of the tile misses).
                        beforeHit += static_cast<double>(start) <= t * (1.0 + 1e-6);
                    }
                }
                for (int i = 0; i < size.x * size.y; ++i) {
                    missTiles += starts[4 * i] >= 3e38f;
                    movedTiles += starts[4 * i] >= 0.0f && starts[4 * i] < 3e38f;
                }
                const RenderedFrame coarseCounted = drawn(tile, true);
                const std::vector<float> counted = readCoarse(gl, renderer);
                double coarseFetches = 0.0, passReads = 0.0;
                for (int i = 0; i < width * height; ++i)
                    coarseFetches += coarseCounted.stats[4 * i + 1];
                for (int i = 0; i < size.x * size.y; ++i) passReads += counted[4 * i + 1];
                const double pixels = double(width) * height;
                std::printf(
                    "    %-40s fetches/pixel %.2f single, %.2f with the pass + %.3f its own; "
                    "tiles moved %zu, missing %zu of %d; worst position error %.2g\n",
                    what.c_str(), singleFetches / pixels, coarseFetches / pixels,
                    passReads / pixels, movedTiles, missTiles, size.x * size.y, worst);
                const std::size_t all = std::size_t(width) * height;
                EXPECT_EQ(sameKind, all) << what;
                EXPECT_EQ(close, all) << what << ": worst " << worst;
                EXPECT_EQ(beforeHit, all) << what;
            }
        }
    }
}

// The pass is the multilevel method's on the plane: another method or base draws the
// single pass.
TEST_F(CoarsePass, OtherMethodsAndBasesDrawTheSinglePass) {
    GlContext& context = test::glContext();
    context.makeCurrent();
    const HeightMap map = synth::cobbles(64, 64, 3);
    OffscreenTarget target(context.gl(), 32, 32);
    ReliefRenderer renderer(context.gl(), shaderDirectory());
    renderer.apply(test::relief(BaseShape::cylinder(), Interpolation::Bilinear, 0.1f), &map,
                   "cobbles");
    renderer.setCoarsePass(8);
    const CameraFrame camera = renderer.resolveCamera(test::orbitCamera(30.0, 30.0, 2.0), 32, 32);
    renderer.draw(camera, ShadingOptions{});
    EXPECT_FALSE(renderer.coarsePassDrawn());
    renderer.apply(test::relief({}, Interpolation::Bilinear, 0.1f), &map, "cobbles");
    renderer.setMethod(MethodSettings{Method::MaxMip});
    renderer.draw(camera, ShadingOptions{});
    EXPECT_FALSE(renderer.coarsePassDrawn());
    renderer.setMethod(MethodSettings{});
    renderer.draw(camera, ShadingOptions{});
    EXPECT_TRUE(renderer.coarsePassDrawn());
}

// Drawn in picture tiles (PictureTile, 40 x 30: not a multiple of the pass's 8) with the
// pass, the picture is the one drawn whole with it, to the same rounding as above: each
// draw's pass covers its own pixels. And the draw leaves the caller's draw framebuffer and
// the texture on the pass's unit as they were.
TEST_F(CoarsePass, PictureTilesAreTheWholePictureAndTheCallersStateStays) {
    GlContext& context = test::glContext();
    context.makeCurrent();
    const GL& gl = context.gl();
    const HeightMap map = synth::cobbles(128, 128, 5);
    const int width = 80, height = 60, tileW = 40, tileH = 30;
    ReliefRenderer renderer(gl, shaderDirectory());
    renderer.apply(test::relief({}, Interpolation::Bilinear, 0.1f), &map, "cobbles");
    renderer.setCoarsePass(8);
    const CameraFrame camera =
        renderer.resolveCamera(test::orbitCamera(8.0, 70.0, 1.0, {0.0, 0.03, 0.0}), width, height);
    OffscreenTarget whole(gl, width, height);
    whole.clear(glm::vec3(0.0f));
    renderer.draw(camera, ShadingOptions{});
    const RenderedFrame expected = whole.read(camera.eye);

    auto marker = gl::Texture::create(gl);
    OffscreenTarget part(gl, tileW, tileH);
    RenderedFrame tiled = expected;
    std::fill(tiled.position.begin(), tiled.position.end(), -1.0f);
    for (int y = 0; y < height; y += tileH) {
        for (int x = 0; x < width; x += tileW) {
            part.clear(glm::vec3(0.0f));
            gl.ActiveTexture(GL_TEXTURE0 + ReliefShader::kCoarseStartUnit);
            gl.BindTexture(GL_TEXTURE_2D, marker.id());
            gl.ActiveTexture(GL_TEXTURE0);
            GLint framebuffer = 0, unitTexture = 0;
            gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
            renderer.draw(camera, ShadingOptions{}, PictureTile{x, y, tileW, tileH});
            ASSERT_TRUE(renderer.coarsePassDrawn());
            GLint framebufferAfter = 0, activeAfter = 0;
            gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebufferAfter);
            gl.GetIntegerv(GL_ACTIVE_TEXTURE, &activeAfter);
            gl.ActiveTexture(GL_TEXTURE0 + ReliefShader::kCoarseStartUnit);
            gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &unitTexture);
            gl.ActiveTexture(GL_TEXTURE0);
            EXPECT_EQ(framebufferAfter, framebuffer);
            EXPECT_EQ(activeAfter, GLint(GL_TEXTURE0));
            EXPECT_EQ(GLuint(unitTexture), marker.id());
            part.readInto(tiled, x, y, tileW, tileH);
        }
    }
    std::size_t same = 0, hits = 0;
    double worst = 0.0;
    for (int row = 0; row < height; ++row) {
        for (int column = 0; column < width; ++column) {
            const float* a = expected.positionAt(column, row);
            const float* b = tiled.positionAt(column, row);
            if (a[3] == 0.0f) {
                same += b[3] == 0.0f;
                continue;
            }
            ++hits;
            const glm::dvec3 pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]);
            const double error = glm::length(pa - pb) / std::max(glm::length(pa), 1e-30);
            worst = std::max(worst, error);
            same += b[3] != 0.0f && error <= 2e-5;
        }
    }
    EXPECT_GT(hits, std::size_t(width * height / 4));
    EXPECT_EQ(same, std::size_t(width * height)) << "worst " << worst;
}

}  // namespace
