// The max pyramids built on the GPU (gl/PyramidBuilder.h) against MaxPyramid on the CPU,
// texel for texel and bit for bit: both pyramids, every level, on maps of odd and
// non-square sizes, 1 x 1 and 4096 x 4096, on the plane and wrapped round a curved base's
// seam, for both interpolations, with heights across the float range (denormals
// included); and after random rectangles of samples change on the GPU, the updated
// pyramids against a CPU build of the samples read back. On the backend named by
// --backend=.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "GlTestBackend.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/ReliefMap.h"
#include "microrelief/gl/ReliefPrograms.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/peers/MaxMipPyramid.h"

using namespace microrelief;

namespace {

class GpuPyramid : public test::GlTest {
protected:
    // The first texel where the GPU's level differs from the CPU's, or "".
    static std::string firstDifference(const std::vector<float>& gpu, const std::vector<float>& cpu,
                                       int width) {
        if (gpu.size() != cpu.size()) return "sizes differ";
        for (std::size_t k = 0; k < gpu.size(); ++k) {
            if (std::bit_cast<std::uint32_t>(gpu[k]) != std::bit_cast<std::uint32_t>(cpu[k])) {
                return "texel " + std::to_string(k % width) + "," + std::to_string(k / width) +
                       ": GPU " + std::to_string(gpu[k]) + " (0x" +
                       std::to_string(std::bit_cast<std::uint32_t>(gpu[k])) + "), CPU " +
                       std::to_string(cpu[k]) + " (0x" +
                       std::to_string(std::bit_cast<std::uint32_t>(cpu[k])) + ")";
            }
        }
        return "";
    }

    // Every level of the windows, and of maxmip's quadtree (peers/MaxMipPyramid.h, made of
    // the CPU pyramid) where the textures have one, the same bits (the GPU's halves times 2^S), the
    // same S and the same top.
    static void expectEqual(const ReliefTextures& textures, const MaxPyramid& cpu,
                            const std::string& what) {
        ASSERT_EQ(cpu.precision(), BoundPrecision::Half);
        ASSERT_EQ(textures.shape().levelCount, cpu.windowLevelCount()) << what;
        ASSERT_EQ(textures.scaleExponent(), cpu.scaleExponent()) << what;
        for (int level = 0; level < cpu.windowLevelCount(); ++level) {
            ASSERT_EQ(firstDifference(textures.readWindowLevel(gl(), level),
                                      cpu.windowLevelData(level), cpu.windowLevelWidth(level)),
                      "")
                << what << ", window level " << level;
        }
        if (textures.hasMaxMipPyramid()) {
            const MaxMipPyramid maxMip(cpu);
            ASSERT_EQ(textures.maxMipShape().levelCount, maxMip.levelCount()) << what;
            for (int level = 0; level < maxMip.levelCount(); ++level) {
                ASSERT_EQ(firstDifference(textures.readAlignedLevel(gl(), level),
                                          maxMip.levelData(level), maxMip.levelWidth(level)),
                          "")
                    << what << ", aligned level " << level;
            }
        }
        EXPECT_EQ(textures.shape().maxHeight, cpu.maxHeight()) << what;
    }

    static MaxPyramid halfPyramid(const HeightMap& map, bool wrapU) {
        return MaxPyramid(map, wrapU, BoundPrecision::Half);
    }

    static PyramidBuilder& builder() {
        static PyramidBuilder instance(gl(), shaderDirectory());
        return instance;
    }
};

// White noise with some of its samples far apart in magnitude: zeros, denormals, huge
// values, so the means keep few bits or need the sticky bit.
HeightMap wideRangeNoise(int width, int height, std::uint32_t seed) {
    HeightMap map = synth::whiteNoise(width, height, seed);
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> pick(0, 7);
    std::uniform_int_distribution<std::uint32_t> denormal(1, 0x7fffffu), exponent(0, 250);
    for (float& h : map.samples) {
        switch (pick(random)) {
            case 0:
                h = 0.0f;
                break;
            case 1:
                h = std::bit_cast<float>(denormal(random));
                break;
            case 2:
                h = std::ldexp(h, static_cast<int>(exponent(random)) - 125);
                break;
            default:
                break;
        }
    }
    return map;
}

// Where a map's textures come from is decided in one place (gl/ReliefMap.h): with a
// pyramid pass that does not compile (a GL error, not the map's), GpuElseCpu builds on the
// CPU (the CPU pyramid's texels) and Gpu throws it; a tiled map is built on the CPU whatever
// was asked (the GPU's passes never run); paging asked for reads the map through pages, and
// refuses tiles in one line naming the map.
TEST_F(GpuPyramid, UploadPolicyFallsBackOnlyForTheGlsFaultAndPagesWhenAsked) {
    test::ScratchDir dir;
    std::filesystem::copy(shaderDirectory(), dir.path(), std::filesystem::copy_options::recursive);
    const std::filesystem::path pass = dir / "pyramid/window_level.frag";
    std::ofstream(pass, std::ios::app) << "\nundeclaredThing();\n";
    ReliefPrograms broken(gl(), dir.path());
    const HeightMap map = synth::cobbles(37, 29, 4);

    MapUploadSettings settings;
    settings.build = PyramidBuild::GpuElseCpu;
    const ReliefTextures fallen = uploadReliefMap(broken, map, nullptr, "cobbles", settings);
    EXPECT_EQ(fallen.paged(), nullptr);
    expectEqual(fallen, halfPyramid(map, false), "the CPU's after a failed GPU build");

    settings.build = PyramidBuild::Gpu;
    try {
        (void)uploadReliefMap(broken, map, nullptr, "cobbles", settings);
        ADD_FAILURE() << "PyramidBuild::Gpu fell back to the CPU";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Runtime) << e.what();
    }

    settings.tiles = {2, 3};
    const ReliefTextures tiled = uploadReliefMap(broken, map, nullptr, "cobbles", settings);
    EXPECT_EQ(tiled.tiles(), glm::ivec2(2, 3));

    ReliefPrograms programs(gl(), shaderDirectory());
    settings.paging.mode = PagingSettings::Mode::Always;
    try {
        (void)uploadReliefMap(programs, map, nullptr, "cobbles", settings);
        ADD_FAILURE() << "a tiled map was read through pages";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_EQ(std::string(e.what()), "cobbles: a map read through pages is not tiled");
    }
    settings.tiles = {1, 1};
    const ReliefTextures paged = uploadReliefMap(programs, map, nullptr, "cobbles", settings);
    EXPECT_NE(paged.paged(), nullptr);
    settings.paging.mode = PagingSettings::Mode::Auto;  // the map is far below the GL's limit
    EXPECT_EQ(uploadReliefMap(programs, map, nullptr, "cobbles", settings).paged(), nullptr);
}

}  // namespace

TEST_F(GpuPyramid, EqualsTheCpuPyramidOnRandomMapsOfAnySize) {
    const std::vector<std::pair<int, int>> sizes = {{1, 1},   {2, 2},   {3, 5},    {17, 4},
                                                    {31, 33}, {100, 7}, {300, 77}, {129, 65},
                                                    {1, 9},   {64, 64}, {33, 257}, {300, 259}};
    for (const bool wrapU : {false, true}) {
        for (auto [w, h] : sizes) {
            const std::uint32_t seed = static_cast<std::uint32_t>(w * 1009 + h);
            for (const bool wide : {false, true}) {
                const HeightMap map =
                    wide ? wideRangeNoise(w, h, seed) : synth::whiteNoise(w, h, seed);
                // The aligned pyramid (maxmip's) on every other map.
                const ReliefTextures textures(gl(), map, "test map", wrapU, builder(),
                                              (w + h) % 2 == 0);
                expectEqual(textures, halfPyramid(map, wrapU),
                            std::to_string(w) + "x" + std::to_string(h) +
                                (wrapU ? " wrapped" : "") + (wide ? ", wide range" : ""));
                if (HasFatalFailure()) return;
            }
        }
    }
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GpuPyramid, EqualsTheCpuPyramidAt4096) {
    const HeightMap map = wideRangeNoise(4096, 4096, 7);
    const ReliefTextures textures(gl(), map, "4096 map", false, builder(), true);
    expectEqual(textures, halfPyramid(map, false), "4096x4096");
}

// Edits in place: rectangles of samples replaced on the GPU (some at the edges and across
// the seam), the pyramids updated over them only; then the samples read back and a CPU
// pyramid built of them from scratch must equal the GPU's, texel for texel.
TEST_F(GpuPyramid, UpdateAfterRandomEditsEqualsACpuBuildOfTheEditedMap) {
    std::mt19937 random(2024);
    const std::vector<std::pair<int, int>> sizes = {{37, 23}, {64, 64}, {5, 130}, {1, 1}};
    for (const bool wrapU : {false, true}) {
        for (auto [w, h] : sizes) {
            HeightMap map = synth::whiteNoise(w, h, static_cast<std::uint32_t>(w + 77 * h));
            ReliefTextures textures(gl(), map, "test map", wrapU, builder(), true);
            std::uniform_int_distribution<int> x(0, w - 1), y(0, h - 1), kind(0, 2);
            std::uniform_real_distribution<float> value(0.0f, 2.0f);
            for (int edit = 0; edit < 12; ++edit) {
                int x0 = x(random), x1 = x(random), y0 = y(random), y1 = y(random);
                if (edit % 4 == 0) x0 = 0;
                if (edit % 4 == 1) x1 = w - 1;
                const TexelRect rect{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1) + 1,
                                     std::max(y0, y1) + 1};
                std::vector<float> values;
                const int k = kind(random);  // lower to 0, raise above the max, or noise
                for (int j = rect.y0; j < rect.y1; ++j) {
                    for (int i = rect.x0; i < rect.x1; ++i) {
                        map.at(i, j) = k == 0   ? 0.0f
                                       : k == 1 ? 3.0f + value(random)
                                                : value(random);
                        values.push_back(map.at(i, j));
                    }
                }
                textures.writeSamples(gl(), rect, values.data());
                builder().update(textures, rect);
                const HeightMap onGpu = textures.readSamples(gl());
                ASSERT_EQ(onGpu.samples, map.samples);
                expectEqual(textures, halfPyramid(onGpu, wrapU),
                            std::to_string(w) + "x" + std::to_string(h) +
                                (wrapU ? " wrapped" : "") + ", edit " + std::to_string(edit));
                if (HasFatalFailure()) return;
            }
        }
    }
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// A map as wide as the GL's textures go has a mip chain to level log2(GL_MAX_TEXTURE_SIZE):
// counting its levels asks no level past that (the GL answers GL_INVALID_VALUE there,
// which a render later reported as its own error).
TEST_F(GpuPyramid, MemoryOfAMapAsWideAsTheTextureLimitLeavesNoGlError) {
    GLint maxTexture = 0;
    gl().GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    const HeightMap map = synth::whiteNoise(maxTexture, 1, 3);
    const ReliefTextures textures(gl(), map, "map", false, builder());
    ASSERT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
    // The R32F samples (one level) and the R16F windows, maxTexture >> k by 1 per level.
    std::size_t windows = 0;
    for (int side = maxTexture; side >= 1; side >>= 1) windows += 2 * side;
    EXPECT_EQ(textures.gpuBytes(gl()), 4 * static_cast<std::size_t>(maxTexture) + windows);
    EXPECT_EQ(gl().GetError(), static_cast<GLenum>(GL_NO_ERROR));
}

// The memory target (issue 16): at most 8 bytes of GPU memory per map texel for any size,
// as the GL reports its textures' levels and formats: the R32F samples and the R16F
// windows, no padding (a size just above a power of two used to cost four times as much);
// the aligned pyramid only where maxmip asks for it.
TEST_F(GpuPyramid, MemoryIsAtMostEightBytesPerMapTexelAtAnySize) {
    const std::vector<std::pair<int, int>> sizes = {{1, 1},     {2, 2},    {3, 1000},
                                                    {257, 129}, {1025, 1}, {4097, 4097}};
    for (auto [w, h] : sizes) {
        const HeightMap map = synth::whiteNoise(w, h, 3);
        const ReliefTextures textures(gl(), map, "map", false, builder());
        const double perTexel =
            static_cast<double>(textures.gpuBytes(gl())) / (static_cast<double>(w) * h);
        std::printf("    %d x %d: %.2f bytes a map texel\n", w, h, perTexel);
        EXPECT_LE(perTexel, 8.0) << w << "x" << h;
        if (w * h > 1000) {
            EXPECT_GE(perTexel, 6.0) << w << "x" << h;  // what is there is counted
        }
    }
}
