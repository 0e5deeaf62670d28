// Loading height maps (scene-and-cli.md, "Height map to surface"): formats, channels,
// normalisation and the refusal of values the relief cannot have.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "TestSupport.h"
#include "core/Error.h"
#include "heightmap/HeightMap.h"

using namespace microrelief;
using microrelief::test::ScratchDir;

namespace {

HeightMap ramp(int w, int h) {
    HeightMap map(w, h);
    for (int j = 0; j < h; ++j) {
        for (int i = 0; i < w; ++i) map.at(i, j) = static_cast<float>(i + w * j) / (w * h - 1);
    }
    return map;
}

// The message of the BadInput error `load` throws; fails the test if it throws nothing.
template <class F>
std::string badInputMessage(F&& load) {
    try {
        load();
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        return e.what();
    }
    ADD_FAILURE() << "expected an Error(BadInput)";
    return {};
}

}  // namespace

TEST(HeightMapLoad, Png8BitIsNormalisedByTypeRange) {
    ScratchDir dir;
    HeightMap source(3, 2);
    source.samples = {0.0f, 1.0f, 128 / 255.0f, 64 / 255.0f, 255 / 255.0f, 1 / 255.0f};
    test::writeMap(dir / "m.png", source, PixelType::UInt8);
    const HeightMap map = loadHeightMap(dir / "m.png");
    ASSERT_EQ(map.width, 3);
    ASSERT_EQ(map.height, 2);
    for (std::size_t k = 0; k < source.samples.size(); ++k)
        EXPECT_NEAR(map.samples[k], source.samples[k], 1e-6);
}

TEST(HeightMapLoad, Png16BitKeepsSixteenBits) {
    ScratchDir dir;
    HeightMap source(2, 1);
    source.samples = {1000 / 65535.0f, 65534 / 65535.0f};
    test::writeMap(dir / "m.png", source, PixelType::UInt16);
    const HeightMap map = loadHeightMap(dir / "m.png");
    EXPECT_NEAR(map.samples[0], 1000 / 65535.0f, 1e-7);
    EXPECT_NEAR(map.samples[1], 65534 / 65535.0f, 1e-7);
}

TEST(HeightMapLoad, FloatExrIsUsedAsStored) {
    ScratchDir dir;
    HeightMap source(2, 2);
    source.samples = {0.0f, 2.5f, 17.25f, 0.125f};
    test::writeMap(dir / "m.exr", source, PixelType::Float);
    EXPECT_EQ(loadHeightMap(dir / "m.exr").samples, source.samples);
}

TEST(HeightMapLoad, RowZeroIsTheFirstRowOfTheFile) {
    ScratchDir dir;
    const HeightMap source = ramp(4, 3);
    test::writeMap(dir / "m.tif", source, PixelType::Float);
    const HeightMap map = loadHeightMap(dir / "m.tif");
    EXPECT_EQ(map.at(0, 0), source.at(0, 0));
    EXPECT_EQ(map.at(3, 2), source.at(3, 2));
    EXPECT_EQ(map.at(1, 2), source.at(1, 2));
}

TEST(HeightMapLoad, ChannelSelectsTheChannel) {
    ScratchDir dir;
    const std::vector<float> rgb = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};  // 2x1, 3 channels
    writeImageAtomically(dir / "rgb.exr", {2, 1, 3, PixelType::Float, rgb.data(), {"R", "G", "B"}});
    HeightMapLoadOptions options;
    options.channel = 2;
    const HeightMap map = loadHeightMap(dir / "rgb.exr", options);
    EXPECT_FLOAT_EQ(map.samples[0], 0.3f);
    EXPECT_FLOAT_EQ(map.samples[1], 0.6f);
    options.channel = 3;
    const std::string message = badInputMessage([&] { loadHeightMap(dir / "rgb.exr", options); });
    EXPECT_NE(message.find("--channel 3"), std::string::npos) << message;
    EXPECT_NE(message.find("3 channel"), std::string::npos) << message;
}

TEST(HeightMapLoad, NormalizeMapsMinMaxToUnitRange) {
    ScratchDir dir;
    HeightMap source(3, 1);
    source.samples = {-2.0f, 0.0f, 6.0f};
    test::writeMap(dir / "m.exr", source, PixelType::Float);
    const HeightMap map = loadHeightMap(dir / "m.exr", {0, true});
    EXPECT_FLOAT_EQ(map.samples[0], 0.0f);
    EXPECT_FLOAT_EQ(map.samples[1], 0.25f);
    EXPECT_FLOAT_EQ(map.samples[2], 1.0f);
}

TEST(HeightMapLoad, NormalizeOfAConstantMapGivesZero) {
    HeightMap map(2, 2, 7.0f);
    prepareHeights(map, {0, true}, "constant");
    for (float h : map.samples) EXPECT_EQ(h, 0.0f);
}

TEST(HeightMapLoad, NegativeValueIsRefusedWithAHint) {
    ScratchDir dir;
    HeightMap source(2, 2, 0.5f);
    source.at(1, 0) = -0.25f;
    test::writeMap(dir / "neg.exr", source, PixelType::Float);
    const std::string message = badInputMessage([&] { loadHeightMap(dir / "neg.exr"); });
    EXPECT_NE(message.find("neg.exr"), std::string::npos) << message;
    EXPECT_NE(message.find("(1, 0)"), std::string::npos) << message;
    EXPECT_NE(message.find("--normalize"), std::string::npos) << message;
}

TEST(HeightMapLoad, NanAndInfAreRefused) {
    ScratchDir dir;
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        HeightMap source(2, 2, 0.5f);
        source.at(0, 1) = bad;
        test::writeMap(dir / "bad.exr", source, PixelType::Float);
        const std::string message = badInputMessage([&] { loadHeightMap(dir / "bad.exr"); });
        EXPECT_NE(message.find("finite"), std::string::npos) << message;
        // --normalize cannot rescue a non-finite value either.
        badInputMessage([&] { loadHeightMap(dir / "bad.exr", {0, true}); });
    }
}

TEST(HeightMapLoad, MissingFileNamesTheFile) {
    const std::string message = badInputMessage([] { loadHeightMap("/nonexistent/map.png"); });
    EXPECT_NE(message.find("/nonexistent/map.png"), std::string::npos);
    EXPECT_NE(message.find("no such file"), std::string::npos);
}

TEST(HeightMapLoad, TruncatedAndGarbageFilesAreRefused) {
    ScratchDir dir;
    test::writeMap(dir / "whole.png", ramp(64, 64), PixelType::UInt16);
    std::vector<std::uint8_t> bytes = test::readBytes(dir / "whole.png");
    bytes.resize(bytes.size() / 2);
    test::writeBytes(dir / "truncated.png", bytes);
    EXPECT_NE(badInputMessage([&] { loadHeightMap(dir / "truncated.png"); }).find("truncated.png"),
              std::string::npos);
    test::writeBytes(dir / "garbage.png",
                     {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
    EXPECT_NE(badInputMessage([&] { loadHeightMap(dir / "garbage.png"); }).find("garbage.png"),
              std::string::npos);
    test::writeBytes(dir / "empty.png", {});
    badInputMessage([&] { loadHeightMap(dir / "empty.png"); });
    badInputMessage([&] { loadHeightMap(dir.path()); });  // a folder
}

TEST(HeightMapLoad, ZeroSizedPngIsRefused) {
    // A PNG signature and an IHDR chunk declaring 0 x 0 pixels.
    ScratchDir dir;
    const std::vector<std::uint8_t> png = {
        0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I',  'H',  'D',  'R', 0,
        0,    0,   0,   0,   0,    0,    0,    8,    0, 0, 0, 0,  0x00, 0x00, 0x00, 0x00};
    test::writeBytes(dir / "zero.png", png);
    badInputMessage([&] { loadHeightMap(dir / "zero.png"); });
}

TEST(HeightMapLoad, OneByOneIsAValidMap) {
    ScratchDir dir;
    HeightMap source(1, 1, 0.75f);
    test::writeMap(dir / "one.exr", source, PixelType::Float);
    const HeightMap map = loadHeightMap(dir / "one.exr");
    ASSERT_EQ(map.width, 1);
    EXPECT_DOUBLE_EQ(map.surface(0.1, 0.9), 0.75);
}

TEST(HeightMapSurface, BilinearBetweenCentresClampedOutside) {
    HeightMap map(2, 2);
    map.samples = {0.0f, 1.0f, 2.0f, 3.0f};        // h00 h10 / h01 h11
    EXPECT_DOUBLE_EQ(map.surface(0.5, 0.5), 0.0);  // sample (0, 0)
    EXPECT_DOUBLE_EQ(map.surface(1.5, 1.5), 3.0);  // sample (1, 1)
    EXPECT_DOUBLE_EQ(map.surface(1.0, 0.5), 0.5);  // halfway along the top row
    EXPECT_DOUBLE_EQ(map.surface(1.0, 1.0), 1.5);  // the middle
    EXPECT_DOUBLE_EQ(map.surface(0.0, 0.0), 0.0);  // clamped corner
    EXPECT_DOUBLE_EQ(map.surface(2.0, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(map.surface(0.1, 1.0), 1.0);  // clamped in X, interpolated in Y
}
