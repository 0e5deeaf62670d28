// A pyramid built a band of rows at a time (core/heightmap/PyramidStream.h) and kept in a
// pyramid file (io/PyramidFile.h): the texels MaxPyramid makes in memory, bit for bit, read
// in order once a pass; a file that is truncated, corrupt or not one is refused, with the
// file named; a map's file reused while the map is unchanged.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Machine.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/heightmap/PyramidPages.h"
#include "microrelief/core/heightmap/PyramidStream.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/io/AtomicFile.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/io/PyramidFile.h"

using namespace microrelief;

namespace {

// `map`'s rows, checking that each pass reads them in order, each once.
MapRows rowsOf(const HeightMap& map, int* passes = nullptr) {
    auto next = std::make_shared<int>(0);
    MapRows rows;
    rows.width = map.width;
    rows.height = map.height;
    rows.read = [&map, next, passes](int y0, int y1, float* out) {
        if (y0 == 0) {
            *next = 0;
            if (passes) ++*passes;
        }
        ASSERT_EQ(y0, *next) << "rows read out of order";
        ASSERT_LT(y0, y1);
        ASSERT_LE(y1, map.height);
        std::copy(map.samples.begin() + static_cast<std::ptrdiff_t>(y0) * map.width,
                  map.samples.begin() + static_cast<std::ptrdiff_t>(y1) * map.width, out);
        *next = y1;
    };
    return rows;
}

std::vector<std::uint32_t> bitsOf(const std::vector<float>& values) {
    std::vector<std::uint32_t> bits;
    for (float v : values) bits.push_back(std::bit_cast<std::uint32_t>(v));
    return bits;
}

// A map with its largest sample in a corner and flat runs, so that edges, the clamp and the
// top all matter.
// The pages of a map as MaxPyramid builds its pyramid (BoundPrecision::Half, untiled), texel
// by texel: the reference the streamed builds (pyramid files, PyramidInMemory) are held to.
class MaxPyramidPages final : public PyramidPages {
public:
    MaxPyramidPages(const HeightMap& map, bool wrapU)
        : PyramidPages(map.width, map.height, wrapU, map.maxValue()),
          map_(map),
          pyramid_(map, wrapU, BoundPrecision::Half) {}

    void read(int level, const TexelRect& rect, float* out) const override {
        const int width = levelSize(level).x;
        const std::vector<float>& data =
            level == 0 ? map_.samples : pyramid_.windowLevelData(level - 1);
        for (int y = rect.y0; y < rect.y1; ++y) {
            const auto from = data.begin() + static_cast<std::ptrdiff_t>(y) * width + rect.x0;
            out = std::copy(from, from + rect.width(), out);
        }
    }

private:
    HeightMap map_;
    MaxPyramid pyramid_;
};

HeightMap testMap(int width, int height, std::uint32_t seed) {
    HeightMap map = synth::valueNoise(width, height, 7.0, 3, seed);
    map.at(width - 1, height - 1) = 1.5f;
    return map;
}

TEST(PyramidStream, GivesEveryRowOfMaxPyramidsLevelsOnceBitForBit) {
    struct Case {
        int width, height;
        bool wrapU;
        int band;
    };
    for (const Case& c : std::vector<Case>{{1, 1, false, 1},
                                           {1, 9, false, 2},
                                           {13, 1, true, 4},
                                           {37, 23, false, 5},
                                           {37, 23, true, 1},
                                           {64, 64, false, 64},
                                           {523, 301, true, 37},
                                           {300, 257, false, 256}}) {
        SCOPED_TRACE(std::to_string(c.width) + " x " + std::to_string(c.height) +
                     (c.wrapU ? " wrapped" : "") + ", bands of " + std::to_string(c.band));
        const HeightMap map = testMap(c.width, c.height, 11);
        const MaxPyramid pyramid(map, c.wrapU, BoundPrecision::Half);
        const std::vector<glm::ivec2> sizes = windowLevelSizes(c.width, c.height);
        std::vector<std::vector<float>> levels(sizes.size() + 1);
        std::vector<int> nextRow(levels.size(), 0);
        const PyramidRowSink sink = [&](int level, int row, const float* texels) {
            ASSERT_LT(level, static_cast<int>(levels.size()));
            ASSERT_EQ(row, nextRow[level]) << "level " << level << "'s rows in order, once";
            ++nextRow[level];
            const int width = sizes[level > 0 ? level - 1 : 0].x;
            levels[level].insert(levels[level].end(), texels, texels + width);
        };
        int passes = 0;
        const StreamedPyramid streamed =
            streamPyramid(rowsOf(map, &passes), c.wrapU, c.band, sink, "test");
        EXPECT_EQ(passes, 2);
        EXPECT_EQ(streamed.scaleExponent, pyramid.scaleExponent());
        EXPECT_EQ(std::bit_cast<std::uint32_t>(streamed.maxHeight),
                  std::bit_cast<std::uint32_t>(pyramid.maxHeight()));
        EXPECT_EQ(streamed.largestSample, map.maxValue());
        EXPECT_EQ(bitsOf(levels[0]), bitsOf(map.samples)) << "the samples";
        for (int k = 0; k < pyramid.windowLevelCount(); ++k) {
            EXPECT_EQ(nextRow[k + 1], sizes[k].y) << "window level " << k << ": every row";
            EXPECT_EQ(bitsOf(levels[k + 1]), bitsOf(pyramid.windowLevelData(k)))
                << "window level " << k;
        }
    }
}

TEST(PyramidStream, RefusesASampleThatIsNotAHeight) {
    HeightMap map = testMap(20, 10, 3);
    map.at(4, 7) = -0.5f;
    try {
        streamPyramid(
            rowsOf(map), false, 4, [](int, int, const float*) {}, "rows.png");
        FAIL() << "a negative sample was taken";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("rows.png: sample (4, 7)"), std::string::npos)
            << e.what();
    }
}

class PyramidFileTest : public ::testing::Test {
protected:
    test::ScratchDir scratch_;
};

// Every texel of every level, read back in rectangles that cross pages, is MaxPyramid's
// (texel by texel).
TEST_F(PyramidFileTest, HoldsTheTexelsOfThePyramidInMemory) {
    for (const bool wrapU : {false, true}) {
        const HeightMap map = testMap(301, 77, 5);
        const std::filesystem::path file = scratch_ / (wrapU ? "w.mrpyr" : "p.mrpyr");
        writePyramidFile(file, rowsOf(map), wrapU, "key", "test", 16);
        const auto read = PyramidFile::open(file);
        const MaxPyramidPages memory(map, wrapU);
        EXPECT_EQ(read->sourceKey(), "key");
        EXPECT_EQ(read->pageSide(), 16);
        EXPECT_EQ(read->wrapsU(), wrapU);
        EXPECT_EQ(read->scaleExponent(), memory.scaleExponent());
        EXPECT_EQ(read->largestSample(), memory.largestSample());
        ASSERT_EQ(read->levelCount(), memory.levelCount());
        std::mt19937 random(3);
        for (int level = 0; level < read->levelCount(); ++level) {
            EXPECT_EQ(bitsOf(read->readLevel(level)), bitsOf(memory.readLevel(level)))
                << "level " << level;
            const glm::ivec2 size = read->levelSize(level);
            for (int trial = 0; trial < 20; ++trial) {
                const int x0 = static_cast<int>(random() % size.x),
                          y0 = static_cast<int>(random() % size.y);
                const TexelRect rect{x0, y0, x0 + 1 + static_cast<int>(random() % (size.x - x0)),
                                     y0 + 1 + static_cast<int>(random() % (size.y - y0))};
                std::vector<float> a(static_cast<std::size_t>(rect.width()) * rect.height()), b = a;
                read->read(level, rect, a.data());
                memory.read(level, rect, b.data());
                ASSERT_EQ(bitsOf(a), bitsOf(b)) << "level " << level << " rect " << rect.x0 << ","
                                                << rect.y0 << " to " << rect.x1 << "," << rect.y1;
            }
        }
    }
}

// The pages of a map in memory built from its rows (the windows alone, the map shared: what
// a map past the GL's textures is drawn from) are MaxPyramid's, bit for bit, on maps one
// sample wide or tall, odd ones and ones over more than one band (256 rows).
TEST_F(PyramidFileTest, TheStreamedPagesInMemoryAreTheMaxPyramids) {
    for (const auto& [w, h] :
         std::vector<std::pair<int, int>>{{1, 1}, {1, 9}, {9, 1}, {2, 2}, {301, 77}, {67, 600}}) {
        for (const bool wrapU : {false, true}) {
            const HeightMap map = testMap(w, h, static_cast<std::uint32_t>(w + 3 * h));
            const auto shared = std::make_shared<const HeightMap>(map);
            const PyramidInMemory streamed(shared, wrapU, "test");
            const MaxPyramidPages built(map, wrapU);
            const std::string what =
                std::to_string(w) + "x" + std::to_string(h) + (wrapU ? " wrapped" : "");
            EXPECT_EQ(&streamed.map(), shared.get()) << what << ": the map copied";
            EXPECT_EQ(streamed.scaleExponent(), built.scaleExponent()) << what;
            EXPECT_EQ(streamed.largestSample(), built.largestSample()) << what;
            ASSERT_EQ(streamed.levelCount(), built.levelCount()) << what;
            for (int level = 0; level < built.levelCount(); ++level) {
                ASSERT_EQ(bitsOf(streamed.readLevel(level)), bitsOf(built.readLevel(level)))
                    << what << ", level " << level;
            }
        }
    }
}

void expectRefused(const std::function<void()>& act, const std::string& expected) {
    try {
        act();
        FAIL() << "not refused: " << expected;
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

TEST_F(PyramidFileTest, ATruncatedOrForeignFileIsRefusedWhenOpened) {
    const HeightMap map = testMap(100, 60, 8);
    const std::filesystem::path file = scratch_ / "map.mrpyr";
    writePyramidFile(file, rowsOf(map), false, "key", "test", 16);
    std::vector<std::uint8_t> bytes = test::readBytes(file);

    const std::filesystem::path cut = scratch_ / "cut.mrpyr";
    test::writeBytes(cut, std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 100));
    expectRefused([&] { PyramidFile::open(cut); }, cut.string() + ": ");
    expectRefused([&] { PyramidFile::open(cut); }, "(truncated)");

    std::vector<std::uint8_t> header = bytes;
    header[12] ^= 1;  // the width
    const std::filesystem::path bad = scratch_ / "header.mrpyr";
    test::writeBytes(bad, header);
    expectRefused([&] { PyramidFile::open(bad); }, bad.string() + ": ");

    header = bytes;
    header[60] ^= 0x40;  // inside the page CRCs: only the header's own CRC-32 can tell
    test::writeBytes(bad, header);
    expectRefused([&] { PyramidFile::open(bad); }, "header is corrupt (its CRC-32 differs)");

    const std::filesystem::path png = scratch_ / "map.png";
    test::writeMap(png, map, PixelType::UInt16);
    expectRefused([&] { PyramidFile::open(png); },
                  png.string() + ": not a microrelief pyramid file");
    expectRefused([&] { PyramidFile::open(scratch_.path()); }, scratch_.path().string());
}

// A page whose bytes changed on disk is refused when it is read, naming the file and the
// page; the other pages are read as before.
TEST_F(PyramidFileTest, ACorruptPageIsRefusedWhenRead) {
    const HeightMap map = testMap(100, 60, 8);
    const std::filesystem::path file = scratch_ / "map.mrpyr";
    writePyramidFile(file, rowsOf(map), false, "key", "test", 16);
    const std::uint64_t pageBytes = 16 * 16 * 4;
    std::vector<std::uint8_t> bytes = test::readBytes(file);
    const std::uint64_t dataOffset =
        bytes.size() - PyramidFile::open(file)->pageCount() * pageBytes;
    bytes[dataOffset + 3 * pageBytes + 1000] ^= 0x01;  // page 3: samples (48..63, 0..15)
    test::writeBytes(file, bytes);

    const auto read = PyramidFile::open(file);
    std::vector<float> texels(16 * 16);
    read->read(0, {0, 0, 16, 16}, texels.data());
    expectRefused(
        [&] {
            read->read(0, {50, 2, 51, 3}, texels.data());
        },
        file.string() + ": page 3 (page level 0) is corrupt");
}

TEST_F(PyramidFileTest, AMapsFileIsBuiltOnceAndAgainWhenTheMapChanges) {
    const HeightMap map = testMap(90, 50, 2);
    const std::filesystem::path png = scratch_ / "terrain.png", cache = scratch_ / "cache";
    test::writeMap(png, map, PixelType::UInt16);
    std::filesystem::create_directories(cache);
    bool built = false;
    const auto first = openOrBuildPyramidFile(png, cache, {}, false, {}, &built);
    EXPECT_TRUE(built);
    const HeightMap loaded = loadHeightMap(png);
    EXPECT_EQ(bitsOf(first->readLevel(0)), bitsOf(loaded.samples)) << "rows as loadHeightMap reads";
    const MaxPyramidPages memory(loaded, false);
    EXPECT_EQ(bitsOf(first->readLevel(1)), bitsOf(memory.readLevel(1)));

    long long reported = 0, total = 0;
    openOrBuildPyramidFile(
        png, cache, {}, false, [&](long long done, long long all) { reported = done, total = all; },
        &built);
    EXPECT_FALSE(built) << "the map is unchanged";
    EXPECT_EQ(reported, 0);

    // The same map normalised is another pyramid, in another file.
    HeightMapLoadOptions normalized;
    normalized.normalize = true;
    const auto other = openOrBuildPyramidFile(png, cache, normalized, false, {}, &built);
    EXPECT_TRUE(built);
    EXPECT_NE(other->path(), first->path());
    EXPECT_EQ(other->largestSample(), 1.0f);

    // A changed map (its time) replaces its file; a build killed before its rename left a
    // temporary (named as io/AtomicFile.h names them, of a process that is gone): removed.
    const pid_t gone = fork();
    if (gone == 0) _exit(0);
    ASSERT_GT(gone, 0);
    waitpid(gone, nullptr, 0);
    const std::filesystem::path left =
        cache / ("." + first->path().stem().string() + ".tmp-" + std::to_string(gone) + "-0.mrpyr");
    test::writeBytes(left, {1, 2, 3});
    ASSERT_EQ(abandonedTemporaryTarget(left), first->path());
    std::filesystem::last_write_time(
        png, std::filesystem::last_write_time(png) + std::chrono::seconds(5));
    openOrBuildPyramidFile(
        png, cache, {}, false, [&](long long done, long long all) { reported = done, total = all; },
        &built);
    EXPECT_TRUE(built);
    EXPECT_EQ(reported, total) << "progress to the end";
    EXPECT_EQ(total, 2 * 50);
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(cache)) {
        (void)entry;
        ++files;
    }
    EXPECT_EQ(files, 2) << "no temporary left, one file per load options";
}

// Rows are read as loadHeightMap reads the whole: integers by their range, a channel, and
// --normalize from [min, max].
TEST_F(PyramidFileTest, AMapFilesRowsAreWhatLoadHeightMapReads) {
    HeightMap map = testMap(70, 40, 9);
    for (float& h : map.samples) h = h * 0.5f + 0.25f;
    const std::filesystem::path exr = scratch_ / "map.exr";
    test::writeMap(exr, map, PixelType::Float);
    for (const bool normalize : {false, true}) {
        HeightMapLoadOptions options;
        options.normalize = normalize;
        const MapRows rows = heightMapFileRows(exr, options).rows;
        ASSERT_EQ(rows.width, 70);
        ASSERT_EQ(rows.height, 40);
        std::vector<float> all(70 * 40);
        for (int pass = 0; pass < 2; ++pass) {
            rows.read(0, 17, all.data());
            rows.read(17, 40, all.data() + 17 * 70);
            EXPECT_EQ(bitsOf(all), bitsOf(loadHeightMap(exr, options).samples))
                << (normalize ? "normalised" : "as stored") << ", pass " << pass;
        }
    }
    expectRefused([&] { heightMapFileRows(scratch_ / "missing.png", {}); }, "missing.png");
}

// A tiled TIFF or OpenEXR (large terrain files usually are) is read by rows of tiles, the
// last tile row and column partial: what loadHeightMap reads (OpenImageIO 2.4 divided by
// zero reading scanlines of one: the program died of SIGFPE).
TEST_F(PyramidFileTest, ATiledMapsRowsAreWhatLoadHeightMapReads) {
    const HeightMap map = testMap(150, 97, 4);
    for (const std::string name : {"tiled.tif", "tiled.exr"}) {
        const std::filesystem::path file = scratch_ / name;
        const bool exr = name.ends_with(".exr");
        OIIO::ImageSpec spec(map.width, map.height, 1,
                             exr ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT16);
        spec.tile_width = spec.tile_height = 32;
        const std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(file.string());
        ASSERT_TRUE(out && out->open(file.string(), spec)) << OIIO::geterror();
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, map.samples.data())) << out->geterror();
        out->close();
        const MapRows rows = heightMapFileRows(file, {}).rows;
        std::vector<float> all(static_cast<std::size_t>(map.width) * map.height);
        for (int y0 = 0; y0 < map.height; y0 += 40) {
            const int y1 = std::min(map.height, y0 + 40);  // bands across tile rows
            rows.read(y0, y1, all.data() + static_cast<std::ptrdiff_t>(y0) * map.width);
        }
        EXPECT_EQ(bitsOf(all), bitsOf(loadHeightMap(file).samples)) << name;
        const std::filesystem::path cache = scratch_ / ("cache-" + name);
        const auto built = openOrBuildPyramidFile(file, cache, {}, false);
        EXPECT_EQ(bitsOf(built->readLevel(0)), bitsOf(all)) << name;
    }
}

// The cache: a file where its folder should be refused; a pyramid file of another version
// built again, not refused; a map copied over with its time kept is another map.
TEST_F(PyramidFileTest, TheCacheRebuildsAnotherVersionAndRefusesAFileForAFolder) {
    const HeightMap map = testMap(40, 30, 1);
    const std::filesystem::path png = scratch_ / "m.png", cache = scratch_ / "cache";
    test::writeMap(png, map, PixelType::UInt16);
    test::writeBytes(scratch_ / "plain", {1});
    expectRefused([&] { openOrBuildPyramidFile(png, scratch_ / "plain", {}, false); },
                  (scratch_ / "plain").string() + ": is not a folder");

    bool built = false;
    const std::filesystem::path file = openOrBuildPyramidFile(png, cache, {}, false)->path();
    std::vector<std::uint8_t> bytes = test::readBytes(file);
    bytes[8] = 99;  // the version
    test::writeBytes(file, bytes);
    expectRefused([&] { PyramidFile::open(file); }, "a pyramid file of version 99");
    openOrBuildPyramidFile(png, cache, {}, false, {}, &built);
    EXPECT_TRUE(built) << "another version is built again";

    // The same size and modification time, other samples (an uncompressed TIFF written
    // over, its time set back): the change time tells.
    const std::filesystem::path tif = scratch_ / "m.tif";
    const auto writeRaw = [&](const HeightMap& heights) {
        OIIO::ImageSpec spec(heights.width, heights.height, 1, OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "none");
        const std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(tif.string());
        ASSERT_TRUE(out && out->open(tif.string(), spec));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, heights.samples.data()));
        out->close();
    };
    writeRaw(map);
    openOrBuildPyramidFile(tif, cache, {}, false);
    const auto time = std::filesystem::last_write_time(tif);
    const auto size = std::filesystem::file_size(tif);
    HeightMap other = map;
    other.at(3, 4) = 0.0f;
    writeRaw(other);
    std::filesystem::last_write_time(tif, time);
    ASSERT_EQ(std::filesystem::file_size(tif), size);
    const auto again = openOrBuildPyramidFile(tif, cache, {}, false, {}, &built);
    EXPECT_TRUE(built) << "a map written over with its old size and time";
    EXPECT_EQ(again->readLevel(0)[4 * 40 + 3], 0.0f);
}

// An interlaced PNG is decoded whole by OpenImageIO at its first row: refused for its rows
// where that is more than half the memory available, from its header alone (a 65536^2 RGBA
// 16-bit one: 32 GiB; here the file is no more than its IHDR), on a machine with 16 GiB
// available (core/Machine.h: the variable stands for it), whatever this one has.
TEST_F(PyramidFileTest, AnInterlacedPngTooLargeToDecodeWholeIsRefusedFromItsHeader) {
    const test::ScopedEnvironment available(kAvailableMemoryVariable, "16384");
    const auto crc32 = [](const std::vector<std::uint8_t>& bytes, std::size_t from) {
        std::uint32_t crc = 0xFFFFFFFFu;
        for (std::size_t k = from; k < bytes.size(); ++k) {
            crc ^= bytes[k];
            for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
        }
        return ~crc;
    };
    std::vector<std::uint8_t> png = {
        0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13,
        'I',  'H', 'D', 'R', 0,    1,    0,    0,    0, 1, 0, 0,  // 65536 x 65536
        16,   6,   0,   0,   1};                                  // 16-bit RGBA, interlaced
    const std::uint32_t crc = crc32(png, 12);
    for (int k = 3; k >= 0; --k) png.push_back(static_cast<std::uint8_t>(crc >> (8 * k)));
    const std::filesystem::path file = scratch_ / "interlaced.png";
    test::writeBytes(file, png);
    expectRefused([&] { heightMapFileRows(file, {}); },
                  file.string() +
                      ": an interlaced PNG, which is decoded whole (32768 MiB, more than half of "
                      "the 16384 MiB available now)");
}

}  // namespace
