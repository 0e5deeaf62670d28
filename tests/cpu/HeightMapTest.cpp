// Loading height maps (scene-and-cli.md, "Height map to surface"): formats, channels,
// normalisation and the refusal of values the relief cannot have.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <limits>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/io/HeightMapFile.h"

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
    EXPECT_NE(message.find("map.load.channel 3"), std::string::npos) << message;
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
    EXPECT_NE(message.find("map.load.normalize"), std::string::npos) << message;
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
    // A TIFF and a JPEG cut off in their pixels, which libtiff and libjpeg read without an
    // error (the missing strips as they are, the missing rows as grey).
    for (const char* name : {"whole.tif", "whole.jpg"}) {
        test::writeMap(dir / name, ramp(64, 64), PixelType::UInt8);
        std::vector<std::uint8_t> image = test::readBytes(dir / name);
        image.resize(image.size() * 2 / 3);
        const std::string cut = std::string("cut-") + name;
        test::writeBytes(dir / cut, image);
        EXPECT_NE(badInputMessage([&] { loadHeightMap(dir / cut); }).find(cut + ": cut off"),
                  std::string::npos)
            << name;
    }
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

// A grazing ray's far end lies ~1e15 texels away: the surface there is the edge's (clamped)
// or a whole number of periods back (repeating), never an overflowed texel index (CI's
// UBSan run caught the int cast of such a coordinate).
TEST(HeightMapSurface, FarCoordinatesAreTheEdgeOrWholePeriodsBack) {
    HeightMap map = ramp(4, 3);
    for (Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Biquadratic}) {
        const MapAddressing clamped{false}, repeating{true};
        for (double far : {1e10, 1e15, 1e300}) {
            EXPECT_EQ(map.surface(far, 1.2, clamped, interpolation),
                      map.surface(4.0, 1.2, clamped, interpolation));
            EXPECT_EQ(map.surface(-far, -far, clamped, interpolation),
                      map.surface(-1.0, -1.0, clamped, interpolation));
            EXPECT_EQ(map.surface(2.25, far, repeating, interpolation),
                      map.surface(2.25, 3.0, repeating, interpolation));
        }
        // 2^40 + 1.25 is exact in a double and four periods of 4 divide 2^40.
        const double shifted = std::ldexp(1.0, 40) + 1.25;
        EXPECT_EQ(map.surface(shifted, 1.7, repeating, interpolation),
                  map.surface(1.25, 1.7, repeating, interpolation));
        EXPECT_EQ(map.surface(-shifted, 1.7, repeating, interpolation),
                  map.surface(4.0 - 1.25, 1.7, repeating, interpolation));
        const double nan = std::numeric_limits<double>::quiet_NaN();
        EXPECT_TRUE(std::isnan(map.surface(nan, 1.0, repeating, interpolation)));
        EXPECT_TRUE(std::isnan(map.surface(1.0, nan, clamped, interpolation)));
    }
}

namespace {

const std::filesystem::path kCorpus = MICRORELIEF_FUZZ_CORPUS_DIR;

// The message of loading `file` (a copy of a corpus file under `name`), which must be
// refused.
std::string refusal(const ScratchDir& dir, const std::string& corpusFile, const std::string& name,
                    const HeightMapLoadOptions& options = {}) {
    std::filesystem::copy_file(kCorpus / corpusFile, dir / name);
    return badInputMessage([&] { loadHeightMap(dir / name, options); });
}

}  // namespace

// Issue 15: inputs that hung or exhausted memory, refused before OpenImageIO reads them.
TEST(HeightMapLoad, WhatIsNotARegularFileIsRefusedBeforeOpening) {
    ScratchDir dir;
    EXPECT_NE(badInputMessage([] { loadHeightMap("/dev/zero"); }).find("not a regular file"),
              std::string::npos);
    // Opening a FIFO for reading would block until a writer came: never, here.
    ASSERT_EQ(::mkfifo((dir / "fifo.png").c_str(), 0600), 0);
    EXPECT_NE(badInputMessage([&] { loadHeightMap(dir / "fifo.png"); }).find("not a regular file"),
              std::string::npos);
}

TEST(HeightMapLoad, SizesBeyondTheLimitAreRefusedFromTheHeader) {
    ScratchDir dir;
    // 69 bytes claiming 65535 x 40000: 10 GB of floats if the header were believed.
    EXPECT_NE(refusal(dir, "claims_65535x40000.png", "a.png")
                  .find("65535 x 40000 is larger than the 16384 x 16384"),
              std::string::npos);
    // The limit is an option (the fuzz target loads at most 2048): a real 64 x 64 map.
    test::writeMap(dir / "m.png", ramp(64, 64), PixelType::UInt16);
    HeightMapLoadOptions small;
    small.maxSide = 32;
    EXPECT_NE(badInputMessage([&] {
                  loadHeightMap(dir / "m.png", small);
              }).find("64 x 64 is larger than the 32 x 32"),
              std::string::npos);
    EXPECT_EQ(loadHeightMap(dir / "m.png").width, 64);
}

// What libpng would call an error is refused first, so that libpng never prints its own
// "libpng error:" line (io/PngCheck.h); each with the reason.
TEST(HeightMapLoad, DamagedPngsAreRefusedBeforeLibpngSeesThem) {
    ScratchDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {"bad_idat_crc.png", "IDAT: CRC error"},
        {"bad_filter.png", "IDAT: bad filter type 7"},
        {"short_data.png", "IDAT: not enough image data"},
        {"truncated_in_idat.png", "IDAT: the file ends inside the chunk (truncated)"},
        {"truncated_in_ihdr.png", "the file ends inside the PNG header"},
        {"palette_without_plte.png", "a palette image without PLTE"},
    };
    for (const auto& [file, reason] : cases) {
        const std::string message = refusal(dir, file, file);
        EXPECT_NE(message.find("not a valid PNG (" + std::string(reason)), std::string::npos)
            << message;
    }
    // Sound files of every colour type and interlacing load.
    for (const char* file : {"grey8_4x4.png", "grey16_3x2.png", "rgba8_2x2.png", "palette1_8x2.png",
                             "adam7_3x3.png", "text_chunk.png"}) {
        EXPECT_NO_THROW(loadHeightMap(kCorpus / file)) << file;
    }
}

// OpenEXR 3.1 allocates what a header claims: attributes that do not fill their size are
// refused first (found by the fuzzer: 1.2 GB allocations from 300-byte files).
TEST(HeightMapLoad, OpenExrHeadersThatLieAreRefused) {
    ScratchDir dir;
    EXPECT_NE(refusal(dir, "found_exr_box2i_size_0.bin", "a.exr").find("has 0 bytes, not 16"),
              std::string::npos);
    EXPECT_NE(refusal(dir, "found_exr_attribute_desync.bin", "b.exr").find("has 144 bytes, not 16"),
              std::string::npos);
    EXPECT_NE(refusal(dir, "truncated_half_4x4.exr", "c.exr").find("not a valid OpenEXR file"),
              std::string::npos);
    EXPECT_NO_THROW(loadHeightMap(kCorpus / "half_4x4.exr"));
}

// One reader, the one the extension names: no probing of every format OpenImageIO has.
TEST(HeightMapLoad, TheExtensionChoosesTheReader) {
    ScratchDir dir;
    EXPECT_NE(refusal(dir, "noise_3x5.tif", "tiff.png").find("Not a PNG file"), std::string::npos);
    EXPECT_NE(refusal(dir, "grey8_4x4.png", "map.img").find("no image format"), std::string::npos);
    EXPECT_NE(refusal(dir, "grey8_4x4.png", "noextension").find("no extension"), std::string::npos);
    std::filesystem::copy_file(kCorpus / "grey8_4x4.png", dir / "UPPER.PNG");
    EXPECT_EQ(loadHeightMap(dir / "UPPER.PNG").width, 4);
}
