// The WebGL 2 page (web/) in a real browser: Debian's Chromium, headless, WebGL 2 through
// SwiftShader, driven over the DevTools protocol (drive_chromium.py), the page served from
// a local HTTP server the driver starts (web/serve.py, the server scripts/web.sh runs).
// Each view is set in the URL; its screenshot is compared with microrelief-render's
// picture of the same view, and the page's "open in microrelief-render" line is run too.
// Bad files go through the page's own drop and file-input paths (the browser's drag
// events with the file, the file input set as a user sets it) and must leave the map.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "BrowserTest.h"
#include "ConeCases.h"
#include "TestSupport.h"
#include "microrelief/core/DataPaths.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/peers/ConeMap.h"

using namespace microrelief;
using browser::jsonString;
using browser::PageRun;
using test::Image;
using test::readImage;

namespace {

// The page and microrelief-render trace the same rays (the page computes the camera and
// every uniform as the C++ does, in doubles, then floats) through the same GLSL, on two
// software GPUs: SwiftShader (ANGLE's translation of GLSL ES 3.00) here, llvmpipe there.
// Both are IEEE single precision, but their pow, exp2, atan, sqrt and division may differ
// in the last bits, and the albedo's mipmaps are made and filtered by each GL its own way.
// Measured over the views below: at most 1 level in any channel without the albedo, up to
// 5 with it (trilinear filtering of the bundled colours) and, in one view of a step-based
// peer on a curved base, 1 pixel of 43 200 off by 21 (a ray between two layers); 8 to 55 %
// of the pixels 1 level apart, the mean 0.03 to 0.34 levels. So:
//  * a pixel is "different" when a channel differs by more than 8 levels (3 % of the range:
//    well above rounding and filtering, well below what another surface, normal or light
//    gives), and at most 0.2 % of the pixels may be (a ray that grazes an edge may hit on
//    one GPU and miss on the other);
//  * the mean difference stays below 0.6 levels (rounding moves at most one level in about
//    half the channels).
// A page that shows nothing (the background), an error, a relief of another height scale
// or map, or another camera fails both by far.
constexpr int kDifferentLevels = 8;
constexpr double kMaxDifferentPixels = 0.002;
constexpr double kMaxMeanDifference = 0.6;

// A PNG written byte by byte: `rows` unfiltered (filter type 0), `chunks` (name, body)
// between IHDR and IDAT. For what OpenImageIO does not write: alpha with gamma, tRNS,
// palettes and grey of fewer than 8 bits.
void writePng(const std::filesystem::path& file, int width, int height, int depth, int colorType,
              const std::vector<std::vector<std::uint8_t>>& rows,
              const std::vector<std::pair<std::string, std::vector<std::uint8_t>>>& chunks = {}) {
    std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    const auto u32 = [](std::vector<std::uint8_t>& v, std::uint32_t x) {
        for (int shift = 24; shift >= 0; shift -= 8)
            v.push_back(static_cast<std::uint8_t>(x >> shift));
    };
    const auto chunk = [&](const std::string& name, const std::vector<std::uint8_t>& body) {
        u32(out, static_cast<std::uint32_t>(body.size()));
        std::vector<std::uint8_t> typed(name.begin(), name.end());
        typed.insert(typed.end(), body.begin(), body.end());
        out.insert(out.end(), typed.begin(), typed.end());
        u32(out,
            static_cast<std::uint32_t>(crc32(0, typed.data(), static_cast<uInt>(typed.size()))));
    };
    std::vector<std::uint8_t> header;
    u32(header, static_cast<std::uint32_t>(width));
    u32(header, static_cast<std::uint32_t>(height));
    header.insert(header.end(), {static_cast<std::uint8_t>(depth),
                                 static_cast<std::uint8_t>(colorType), 0, 0, 0});
    chunk("IHDR", header);
    for (const auto& [name, body] : chunks) chunk(name, body);
    std::vector<std::uint8_t> raw;
    for (const auto& row : rows) {
        raw.push_back(0);
        raw.insert(raw.end(), row.begin(), row.end());
    }
    uLongf size = compressBound(static_cast<uLong>(raw.size()));
    std::vector<std::uint8_t> packed(size);
    compress(packed.data(), &size, raw.data(), static_cast<uLong>(raw.size()));
    packed.resize(size);
    chunk("IDAT", packed);
    chunk("IEND", {});
    test::writeBytes(file, out);
}

std::vector<std::uint8_t> bigEndian16(std::initializer_list<unsigned> values) {
    std::vector<std::uint8_t> bytes;
    for (unsigned v : values)
        bytes.insert(bytes.end(),
                     {static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)});
    return bytes;
}

// A view as the page's URL and as microrelief-render's flags.
struct View {
    std::string name, query, flags;
    int width, height;
};

class WebPage : public browser::BrowserTest {
protected:
    static constexpr browser::PictureThresholds kLimits = {kDifferentLevels, kMaxDifferentPixels,
                                                           kMaxMeanDifference};

    // One browser for all: each view opened, awaited, photographed, its command read; then
    // `more` (steps whose outcomes are numbered from 4 * views.size() on). Each picture
    // against microrelief-render's, and the page's "open in microrelief-render" line drawing
    // the test's picture exactly.
    PageRun expectViewsMatchTheRenderer(const std::vector<View>& views,
                                        const std::string& more = "") {
        std::string steps = "[";
        for (std::size_t k = 0; k < views.size(); ++k) {
            const View& v = views[k];
            steps += (k ? ", " : "") + open(v.query, v.width, v.height) +
                     ", {\"wait\": \"ready\"}, {\"screenshot\": " +
                     jsonString((dir / (v.name + "-page.png")).string()) +
                     "}, {\"eval\": \"document.getElementById('command').textContent\"}";
        }
        const PageRun page = runPage(steps + more + "]");
        for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());

        for (std::size_t k = 0; k < views.size(); ++k) {
            const View& v = views[k];
            const int step = 4 * static_cast<int>(k);
            SCOPED_TRACE(v.name);
            EXPECT_EQ(page.at(step + 1, "state"), "ready") << page.at(step + 1, "error");
            if (page.at(step + 1, "state") != "ready") continue;
            EXPECT_EQ(page.at(step + 1, "map"), "cobbles.png");
            const auto rendered = dir / (v.name + "-render.png");
            const std::string flags = v.flags + " --size " + size(v.width, v.height);
            render(flags, rendered);
            expectSamePicture(v.name, dir / (v.name + "-page.png"), rendered,
                              "microrelief-render " + flags, kLimits);

            const std::string command = page.at(step + 3, "value");
            const std::string program = "microrelief-render ";
            EXPECT_EQ(command.rfind(program, 0), 0u) << command;
            if (command.rfind(program, 0) != 0) continue;
            const auto printed = dir / (v.name + "-printed.png");
            render(command.substr(program.size()), printed);
            const Image a = readImage(printed), b = readImage(rendered);
            EXPECT_EQ(a.width, b.width) << command;
            EXPECT_EQ(a.pixels, b.pixels)
                << "the page's command draws another picture: " << command;
        }
        return page;
    }
};

// Several cameras in the URL, each picture against microrelief-render's: the default view
// (the bundled colours), grazing with hard shadows, straight down with the spec's
// orientation, the maxmip and pom peers, a cylinder with the biquadratic last level, a
// sphere with soft shadows.
TEST_F(WebPage, ViewsSetInTheUrlMatchTheRenderer) {
    const std::vector<View> views = {
        {"default", "", "", 240, 180},
        {"grazing-shadows", "eye=0.75,0.1,0.55&target=-0.2,0.02,-0.1&fovy=50&shadows=hard",
         "--eye=0.75,0.1,0.55 --target=-0.2,0.02,-0.1 --fovy 50 --shadows hard", 240, 180},
        {"top-down", "eye=0,1.6,0&target=0,0,0&up=0,0,-1&albedo=none",
         "--eye=0,1.6,0 --target=0,0,0 --up=0,0,-1 --albedo none", 160, 160},
        {"maxmip", "method=maxmip&albedo=none&eye=-0.7,0.45,0.6&light=0.3,0.5,0.8",
         "--method maxmip --albedo none --eye=-0.7,0.45,0.6 --light=0.3,0.5,0.8", 200, 150},
        {"pom", "method=pom&steps=24&eye=0.5,0.7,-0.6",
         "--method pom --steps 24 --eye=0.5,0.7,-0.6", 200, 150},
        {"cylinder-biquadratic",
         "base=cylinder&radius=0.25&length=0.9&interpolation=biquadratic&eye=0.7,0.4,0.9&target=0,"
         "0,0",
         "--base cylinder --radius 0.25 --length 0.9 --interpolation biquadratic "
         "--eye=0.7,0.4,0.9 --target=0,0,0",
         200, 150},
        {"sphere-soft-shadows",
         "base=sphere&shadows=soft&light-size=4&albedo=none&target=0,0,0&height-scale=0.15",
         "--base sphere --shadows soft --light-size 4 --albedo none --target=0,0,0 "
         "--height-scale 0.15",
         200, 150},
    };
    // And a URL with a bad value: an error on the page, nothing else.
    const PageRun page = expectViewsMatchTheRenderer(
        views, ", " + open("method=fastest", 64, 48) + ", {\"wait\": \"ready\"}");
    const int bad = 4 * static_cast<int>(views.size()) + 1;
    EXPECT_EQ(page.at(bad, "state"), "error");
    EXPECT_NE(page.at(bad, "error").find("method=fastest"), std::string::npos)
        << page.at(bad, "error");
}

// A key the page does not know (a typo) is an error naming it, not a view drawn without it.
TEST_F(WebPage, AnUnknownUrlKeyIsAnErrorNamingIt) {
    const PageRun page =
        runPage("[" + open("pixelerror=2", 64, 48) + ", {\"wait\": \"ready\"}, " +
                open("eye=0,1,0&target=0,1,0", 64, 48) + ", {\"wait\": \"ready\"}, " +
                open("up=1,1,1&eye=2,2,2&target=0,0,0", 64, 48) + ", {\"wait\": \"ready\"}, " +
                open("fovy=180", 64, 48) + ", {\"wait\": \"ready\"}]");
    EXPECT_EQ(page.at(1, "state"), "error");
    EXPECT_NE(page.at(1, "error").find("the URL: pixelerror: not a key this page knows ("),
              std::string::npos)
        << page.at(1, "error");
    // A camera that cannot be drawn, in the programs' words with the keys for their flags
    // (not "drawing failed").
    EXPECT_EQ(page.at(3, "state"), "error");
    EXPECT_NE(page.at(3, "error").find("the URL: eye and target must differ"), std::string::npos)
        << page.at(3, "error");
    EXPECT_NE(page.at(5, "error").find("the URL: up must not be parallel to the view direction"),
              std::string::npos)
        << page.at(5, "error");
    EXPECT_NE(page.at(7, "error").find("the URL: fovy must lie strictly between 0 and 180"),
              std::string::npos)
        << page.at(7, "error");
}

// Views the programs refuse (issue 47) are refused by the page too, with the programs'
// checks and their messages (web/scene_checks.js; every case's message against
// microrelief-render's is tests/web/scene_checks_test.mjs): a field of view whose pixels'
// rays float cannot tell apart, a relief's top and a base's length past what float holds.
// Each is an error naming the keys and the state says so, not "ready" over a blank canvas.
TEST_F(WebPage, ViewsTheProgramsRefuseAreRefusedWithTheirMessages) {
    const struct {
        std::string query, expected;
    } cases[] = {
        {"fovy=1e-37",
         "the URL: fovy 1e-37 at a picture 48 pixels high: neighbouring pixels' rays"},
        {"height-scale=1e30", "the URL: cobbles.png: the relief's top (height-scale 1e+30 x "},
        {"base=cylinder&length=1e8",
         "the URL: cobbles.png: the relief's box on base cylinder radius 0.3 length 1e+08"},
    };
    std::string steps;
    for (const auto& c : cases)
        steps += (steps.empty() ? "" : ", ") + open(c.query, 64, 48) + ", {\"wait\": \"ready\"}";
    const PageRun page = runPage("[" + steps + "]");
    for (std::size_t k = 0; k < std::size(cases); ++k) {
        SCOPED_TRACE(cases[k].query);
        const int step = 2 * static_cast<int>(k) + 1;
        EXPECT_EQ(page.at(step, "state"), "error");
        EXPECT_NE(page.at(step, "error").find(cases[k].expected), std::string::npos)
            << page.at(step, "error");
        EXPECT_EQ(page.at(step, "error").find('\n'), std::string::npos) << "one line";
    }
}

// The orbit camera: a drag turns the view, the wheel zooms, a Shift drag pans (the browser's
// own mouse events). The view lands in the URL and in the command line: the URL opened
// again shows the same picture to the bit, and the command draws it as the thresholds
// above allow.
TEST_F(WebPage, OrbitZoomAndPanWriteTheViewToTheUrl) {
    const int width = 200, height = 150;
    const PageRun moved = runPage(
        "[" + open("", width, height) +
        ", {\"wait\": \"ready\"}, {\"drag\": [100, 75, 160, 60]}, {\"wheel\": [100, 75, -200]},"
        " {\"drag\": [100, 75, 80, 90], \"shift\": true}, {\"wait\": \"frames\", \"above\": 1},"
        " {\"screenshot\": " +
        jsonString((dir / "moved.png").string()) +
        "}, {\"eval\": \"location.search.slice(1)\"},"
        " {\"eval\": \"document.getElementById('command').textContent\"}]");
    ASSERT_EQ(moved.at(5, "state"), "ready") << moved.at(5, "error");
    const std::string query = moved.at(7, "value"), command = moved.at(8, "value");
    EXPECT_EQ(query.find("eye=0.8,0.5,0.85&"), std::string::npos)
        << "the eye did not move: " << query;
    EXPECT_EQ(query.find("target=0,-0.03,0&"), std::string::npos)
        << "the target did not pan: " << query;

    const PageRun again =
        runPage("[{\"open\": " + jsonString(query) + ", \"size\": [" + std::to_string(width) +
                ", " + std::to_string(height) + "]}, {\"wait\": \"ready\"}, {\"screenshot\": " +
                jsonString((dir / "again.png").string()) + "}]");
    ASSERT_EQ(again.at(1, "state"), "ready") << again.at(1, "error");
    const Image a = readImage(dir / "moved.png"), b = readImage(dir / "again.png");
    ASSERT_GT(a.width, 0);
    ASSERT_EQ(a.width, b.width);
    EXPECT_EQ(a.pixels, b.pixels) << "the URL does not hold the view: " << query;

    const std::string program = "microrelief-render ";
    ASSERT_EQ(command.rfind(program, 0), 0u) << command;
    render(command.substr(program.size()), dir / "moved-render.png");
    expectSamePicture("orbited", dir / "moved.png", dir / "moved-render.png", command, kLimits);
}

// Files that are not height maps, dropped on the page or chosen with its file input (the
// browser's own drag events carrying the file; the file input set as a user sets it, which
// fires its change event): each refused with the file's name and the reason, shown on the
// page, and the bundled map kept, its picture unchanged to the last bit.
TEST_F(WebPage, BadFilesShowAnErrorAndKeepTheMap) {
    const std::filesystem::path corpus = MICRORELIEF_FUZZ_CORPUS_DIR;
    test::writeBytes(dir / "notes.txt",
                     {'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'});
    // The bundled map cut in the middle of its image data.
    const std::vector<std::uint8_t> whole = test::readBytes(defaultHeightMapPath());
    test::writeBytes(dir / "cut.png",
                     std::vector<std::uint8_t>(whole.begin(), whole.begin() + whole.size() / 2));
    struct Bad {
        std::filesystem::path file;
        const char* how;
        const char* reason;
    };
    const std::vector<Bad> bad = {
        {dir / "notes.txt", "drop", "not a PNG file"},
        {dir / "cut.png", "choose", "truncated"},
        {corpus / "bad_idat_crc.png", "drop", "bad CRC"},
        {corpus / "truncated_in_idat.png", "choose", "truncated"},
        {corpus / "short_data.png", "drop", "not enough image data"},
        {corpus / "claims_65535x40000.png", "choose", "larger than"},
        {corpus / "adam7_3x3.png", "drop", "interlaced"},
        {corpus / "bad_filter.png", "choose", "bad filter type"},
    };
    std::string steps = "[" + open("", 200, 150) + ", {\"wait\": \"ready\"}, {\"screenshot\": " +
                        jsonString((dir / "before.png").string()) + "}";
    for (std::size_t k = 0; k < bad.size(); ++k) {
        steps += ", {\"" + std::string(bad[k].how) + "\": " + jsonString(bad[k].file.string()) +
                 "}, {\"wait\": \"opened\", \"above\": " + std::to_string(k) + "}";
    }
    steps += ", {\"screenshot\": " + jsonString((dir / "after.png").string()) + "}]";
    const PageRun page = runPage(steps);
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");

    for (std::size_t k = 0; k < bad.size(); ++k) {
        const int step = 4 + 2 * static_cast<int>(k);
        const std::string name = bad[k].file.filename().string();
        const std::string message = page.at(step, "mapError");
        SCOPED_TRACE(name + " (" + bad[k].how + ")");
        EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << "the message names the file: " << message;
        EXPECT_NE(message.find(bad[k].reason), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        EXPECT_EQ(page.at(step, "shownMapError"), message) << "shown on the page";
        EXPECT_EQ(page.at(step, "map"), "cobbles.png") << "the map was kept";
        EXPECT_EQ(page.at(step, "state"), "ready");
    }
    const Image before = readImage(dir / "before.png"), after = readImage(dir / "after.png");
    ASSERT_GT(before.width, 0);
    ASSERT_EQ(before.width, after.width);
    EXPECT_EQ(before.pixels, after.pixels) << "the picture changed after a refused file";
}

// Maps that are good, dropped or chosen: each becomes the map, its samples exactly what
// microrelief-render's loader reads through OpenImageIO: 8 and 16 bits; grey, grey and
// alpha, RGB, RGBA, palettes, grey of 1 to 4 bits; alpha multiplied in (every 8-bit value
// and alpha pair, in integers, and with a gAMA chunk's gamma, which an sRGB chunk
// overrides), tRNS keys and palette alphas. And a non-square 16-bit map's picture matches
// microrelief-render's.
TEST_F(WebPage, DroppedMapsAreTheLoadersSamplesAndRenderAlike) {
    const std::filesystem::path corpus = MICRORELIEF_FUZZ_CORPUS_DIR;
    const HeightMap noise = synth::valueNoise(96, 64, 12.0, 3, 7);
    test::writeMap(dir / "noise16.png", noise, PixelType::UInt16);
    test::writeMap(dir / "noise8.png", synth::valueNoise(9, 7, 3.0, 2, 3), PixelType::UInt8);
    // Every 8-bit (value, alpha) pair: value x, alpha y.
    std::vector<std::vector<std::uint8_t>> pairs8(256);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x)
            pairs8[y].insert(pairs8[y].end(),
                             {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y)});
    writePng(dir / "alpha8.png", 256, 256, 8, 4, pairs8);
    writePng(dir / "alpha8-gamma.png", 256, 256, 8, 4, pairs8,
             {{"gAMA", {0, 0, 0xb1, 0x8f}}});  // 45455: 2.2
    writePng(dir / "alpha8-gamma-srgb.png", 256, 256, 8, 4, pairs8,
             {{"gAMA", {0, 0, 0xd9, 0x04}}, {"sRGB", {0}}});
    // 16-bit grey and alpha, RGBA: scattered values, alphas from 0 to 65535.
    std::vector<std::vector<std::uint8_t>> grey16(32), rgba16(16);
    std::uint32_t state = 12345;
    const auto next = [&] { return (state = state * 1664525u + 1013904223u) >> 16; };
    for (auto& row : grey16)
        for (int x = 0; x < 64; ++x) {
            const unsigned alpha = x % 8 == 0 ? (x % 16 ? 65535u : 0u) : next();
            const auto bytes = bigEndian16({next(), alpha});
            row.insert(row.end(), bytes.begin(), bytes.end());
        }
    writePng(dir / "alpha16.png", 64, 32, 16, 4, grey16);
    writePng(dir / "alpha16-gamma.png", 64, 32, 16, 4, grey16,
             {{"gAMA", {0, 0, 0xd9, 0x04}}});  // 55556: 1.8
    for (auto& row : rgba16)
        for (int x = 0; x < 8; ++x) {
            const auto bytes = bigEndian16({next(), next(), next(), next()});
            row.insert(row.end(), bytes.begin(), bytes.end());
        }
    writePng(dir / "rgba16.png", 8, 16, 16, 6, rgba16);
    // tRNS: a 2-bit grey key, an RGB key at 16 bits, a palette's alphas (4 colours, 2 bits).
    writePng(dir / "grey2-trns.png", 4, 2, 2, 0, {{0x1b}, {0xe4}}, {{"tRNS", {0, 2}}});
    writePng(dir / "rgb16-trns.png", 3, 1, 16, 2, {bigEndian16({1, 2, 3, 4, 5, 6, 1, 2, 4})},
             {{"tRNS", bigEndian16({1, 2, 3})}});
    writePng(
        dir / "palette2-trns.png", 4, 2, 2, 3, {{0x1b}, {0xb1}},
        {{"PLTE", {10, 20, 30, 200, 100, 50, 255, 255, 255, 0, 0, 0}}, {"tRNS", {255, 128, 0}}});
    writePng(dir / "grey4.png", 4, 1, 4, 0, {{0x3c, 0xf0}});

    const std::vector<std::filesystem::path> maps = {
        dir / "noise8.png",        dir / "alpha8.png",
        dir / "alpha8-gamma.png",  dir / "alpha8-gamma-srgb.png",
        dir / "alpha16.png",       dir / "alpha16-gamma.png",
        dir / "rgba16.png",        dir / "grey2-trns.png",
        dir / "rgb16-trns.png",    dir / "palette2-trns.png",
        dir / "grey4.png",         corpus / "rgba8_2x2.png",
        corpus / "grey16_3x2.png", corpus / "palette1_8x2.png",
        dir / "noise16.png",
    };
    const int width = 200, height = 150;
    std::string steps = "[" + open("", width, height) + ", {\"wait\": \"ready\"}";
    for (std::size_t k = 0; k < maps.size(); ++k) {
        steps += std::string(", {\"") + (k % 2 ? "choose" : "drop") +
                 "\": " + jsonString(maps[k].string()) +
                 "}, {\"wait\": \"opened\", \"above\": " + std::to_string(k) +
                 "}, {\"eval\": \"Array.from(microrelief.map.samples).join(' ')\"}";
    }
    steps += ", {\"screenshot\": " + jsonString((dir / "noise16-page.png").string()) +
             "}, {\"eval\": \"document.getElementById('command').textContent\"}"
             ", {\"eval\": \"['checked', 'disabled'].map((k) => "
             "document.getElementById('albedo')[k]).join(' ')\"}]";
    const PageRun page = runPage(steps);
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");

    for (std::size_t k = 0; k < maps.size(); ++k) {
        const int step = 3 + 3 * static_cast<int>(k);
        const std::string name = maps[k].filename().string();
        SCOPED_TRACE(name);
        EXPECT_EQ(page.at(step, "mapError"), "");
        EXPECT_EQ(page.at(step, "map"), name);
        EXPECT_EQ(page.at(step, "state"), "ready") << page.at(step, "error");
        const HeightMap expected = loadHeightMap(maps[k]);
        std::istringstream values(page.at(step + 1, "value"));
        std::vector<float> samples;
        for (double value; values >> value;) samples.push_back(static_cast<float>(value));
        ASSERT_EQ(samples.size(), expected.samples.size());
        std::size_t differ = 0, first = samples.size();
        for (std::size_t i = 0; i < samples.size(); ++i) {
            if (samples[i] == expected.samples[i]) continue;
            ++differ;
            first = std::min(first, i);
        }
        EXPECT_EQ(differ, 0u) << "the page's samples differ from the loader's, first at " << first
                              << ": " << (differ ? samples[first] : 0.0f) << " against "
                              << (differ ? expected.samples[first] : 0.0f);
    }
    // The last map's picture: the page's command names the file as dropped.
    const std::string command = page.at(3 + 3 * static_cast<int>(maps.size()), "value");
    EXPECT_NE(command.find("--height noise16.png "), std::string::npos) << command;
    // The bundled map's colours are not drawn on a map of the user's: their box not ticked.
    EXPECT_EQ(page.at(4 + 3 * static_cast<int>(maps.size()), "value"), "false true");
    const auto rendered = dir / "noise16-render.png";
    const std::string flags =
        "--height " + (dir / "noise16.png").string() + " --size " + size(width, height);
    render(flags, rendered);
    expectSamePicture("noise16", dir / "noise16-page.png", rendered, "microrelief-render " + flags,
                      kLimits);
}

// Every variant of relief.frag the page offers (each method on each base it runs on, both
// last levels, shadows where the method traces the solid, the albedo) compiles and links under the
// browser's WebGL 2 (ANGLE's GLSL ES 3.00 front end, stricter than glslangValidator).
TEST_F(WebPage, EveryVariantCompilesInTheBrowser) {
    const std::string loop =
        "(async () => { const failed = []; let count = 0;"
        " for (const base of ['plane', 'cylinder', 'ellipsoid'])"
        " for (const method of ['multilevel', 'normal', 'offset', 'steep', 'pom', 'relief', "
        "'maxmip', 'cone', 'rcsm'])"
        " for (const interpolation of ['bilinear', 'biquadratic'])"
        " for (const shadows of ['off', 'hard', 'soft'])"
        " for (const albedoMap of [false, true]) {"
        "  if (base !== 'plane' && !['multilevel', 'maxmip', 'pom', 'relief'].includes(method)) "
        "continue;"
        "  if (shadows !== 'off' && !['multilevel', 'maxmip', 'cone'].includes(method)) continue;"
        "  ++count;"
        "  try { await microrelief.renderer.program({method, base, interpolation, shadows, "
        "albedoMap}); }"
        "  catch (e) { failed.push(e.message); } }"
        " return count + ' ' + failed.join(' // '); })()";
    const PageRun page = evalOnReadyPage(loop);
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    // 9 methods x 2 levels x 2 albedos on the plane with shadows off, 2 shadow modes for 3
    // of them (multilevel, maxmip, cone); on each curved base 4 methods, shadows for 2.
    EXPECT_EQ(page.at(2, "value"), "124 ");
}

// The peers cone and rcsm in the page, against microrelief-render: their cone maps made in the
// page (cone's on the GPU, rcsm's by the C++ build in WebAssembly), only once the method is
// chosen (the URL here), the state "loading" until then. Cone is exact like the multilevel
// method and traces the solid (shadows too); rcsm steps through its relaxed cones, reads
// them filtered, and ends in a binary search, so a filtered read that one GPU rounds
// otherwise than the other can move a hit: the same thresholds as the other views (kLimits)
// hold for both, as measured here (the log prints the numbers).
TEST_F(WebPage, ConeAndRcsmMatchTheRenderer) {
    const std::vector<View> views = {
        {"cone", "method=cone", "--method cone", 200, 150},
        {"cone-grazing-shadows",
         "method=cone&eye=0.75,0.1,0.55&target=-0.2,0.02,-0.1&fovy=50&shadows=hard&albedo=none",
         "--method cone --eye=0.75,0.1,0.55 --target=-0.2,0.02,-0.1 --fovy 50 --shadows hard "
         "--albedo none",
         200, 150},
        {"rcsm", "method=rcsm&albedo=none&eye=-0.7,0.45,0.6&light=0.3,0.5,0.8",
         "--method rcsm --albedo none --eye=-0.7,0.45,0.6 --light=0.3,0.5,0.8", 200, 150},
        {"rcsm-15-steps", "method=rcsm&steps=15&eye=0.5,0.7,-0.6",
         "--method rcsm --steps 15 --eye=0.5,0.7,-0.6", 200, 150},
    };
    expectViewsMatchTheRenderer(views);
}

// A cone map as the page's GPU holds it (ReliefTextures.readConeMap: "apex ratio apex ratio
// ..." per texel, row 0 first), as a ConeMap: halves, so exact in the text and in floats.
ConeMap pageConeMap(const std::string& pageTexels) {
    std::istringstream values(pageTexels);
    ConeMap cones;
    for (double apex, ratio; values >> apex >> ratio;) {
        cones.apex.push_back(static_cast<float>(apex));
        cones.ratio.push_back(static_cast<float>(ratio));
    }
    return cones;
}

// A cone map of the page against the C++ build's, value for value: both are halves, so equal
// values are equal bits.
void expectSameConeMap(const std::string& name, const std::string& pageTexels,
                       const ConeMap& expected) {
    const ConeMap page = pageConeMap(pageTexels);
    const std::size_t count = expected.apex.size();
    ASSERT_EQ(page.apex.size(), count) << name << ": not the map's size";
    std::size_t differ = 0, first = count;
    for (std::size_t k = 0; k < count; ++k) {
        if (page.apex[k] == expected.apex[k] && page.ratio[k] == expected.ratio[k]) continue;
        ++differ;
        first = std::min(first, k);
    }
    std::printf("    %-22s %zu texels, %zu differ\n", name.c_str(), count, differ);
    EXPECT_EQ(differ, 0u) << name << ": first at texel " << first << ": page ("
                          << (differ ? page.apex[first] : 0.0f) << ", "
                          << (differ ? page.ratio[first] : 0.0f) << "), C++ ("
                          << (differ ? expected.apex[first] : 0.0f) << ", "
                          << (differ ? expected.ratio[first] : 0.0f) << ")";
}

// The page's cone maps against the C++ build's (peers/ConeMap.h, what the programs' tests
// hold conservative or relaxed), of the bundled map and of a dropped 37 x 23 map (odd
// sizes: the pyramid walk's padding), read back from the RG16F textures the page draws
// with: rcsm's relaxed map, the C++ itself in WebAssembly, to the bit; cone's conservative
// map, drawn on the GPU (cone_map.frag), every apex the same and no ratio wider, most
// the same (test::GpuConeMapCheck, as tests/gl holds the programs' GPU build). The page
// builds each only when its method is chosen: none before, the one chosen after; the
// panel says where each was built, and the WebAssembly build reported its rows as it went.
TEST_F(WebPage, ThePageConeMapsAreTheCppOnes) {
    const auto noise = dir / "noise37.png";
    test::writeMap(noise, synth::valueNoise(37, 23, 5.0, 3, 11), PixelType::UInt16);
    // The method chosen in the panel, as a user chooses it (a change event).
    const auto choose = [](const std::string& method) {
        return "{\"eval\": \"(() => { const m = document.getElementById('method'); m.value = '" +
               method + "'; m.dispatchEvent(new Event('change')); return m.value; })()\"}";
    };
    const auto readConeMap = [](const std::string& kind) {
        return "{\"eval\": \"Array.from(microrelief.renderer.textures.readConeMap('" + kind +
               "')).join(' ')\"}";
    };
    const std::string ready = "{\"wait\": \"ready\"}",
                      coneMaps = "{\"eval\": \"document.documentElement.dataset.coneMaps\"}",
                      panel = "{\"eval\": \"document.getElementById('cone-maps').textContent\"}",
                      progress = "{\"eval\": \"microrelief.coneProgress.relaxed.join(' ')\"}";
    // Steps 0-2: no cone map yet; 3-6: cone's; 7-10: rcsm's; 11-15: a new map, rcsm's
    // alone; 16-18: cone's of the new map; 19-20: the panel's line, rcsm's reports.
    const std::vector<std::string> steps = {open("", 64, 48),
                                            ready,
                                            coneMaps,
                                            choose("cone"),
                                            ready,
                                            coneMaps,
                                            readConeMap("conservative"),
                                            choose("rcsm"),
                                            ready,
                                            coneMaps,
                                            readConeMap("relaxed"),
                                            "{\"drop\": " + jsonString(noise.string()) + "}",
                                            "{\"wait\": \"opened\", \"above\": 0}",
                                            ready,
                                            readConeMap("relaxed"),
                                            coneMaps,
                                            choose("cone"),
                                            ready,
                                            readConeMap("conservative"),
                                            panel,
                                            progress};
    std::string json = "[";
    for (const std::string& step : steps) json += (json.size() > 1 ? ", " : "") + step;
    const PageRun page = runPage(json + "]");
    for (const std::string& line : page.log) std::printf("    page: %s\n", line.c_str());
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    EXPECT_EQ(page.at(2, "value"), "") << "a cone map before cone or rcsm was chosen";
    EXPECT_EQ(page.at(3, "value"), "cone");
    ASSERT_EQ(page.at(4, "state"), "ready") << page.at(4, "error");
    EXPECT_EQ(page.at(5, "value"), "conservative");
    ASSERT_EQ(page.at(8, "state"), "ready") << page.at(8, "error");
    EXPECT_EQ(page.at(9, "value"), "conservative relaxed");
    ASSERT_EQ(page.at(13, "state"), "ready") << page.at(13, "error");
    EXPECT_EQ(page.at(13, "map"), "noise37.png");
    EXPECT_EQ(page.at(15, "value"), "relaxed") << "the new map's cone maps: rcsm's alone";
    ASSERT_EQ(page.at(17, "state"), "ready") << page.at(17, "error");

    const HeightMap bundled = loadHeightMap(defaultHeightMapPath());
    const HeightMap dropped = loadHeightMap(noise);
    expectSameConeMap("bundled relaxed", page.at(10, "value"), buildRelaxedConeMap(bundled));
    expectSameConeMap("noise37 relaxed", page.at(14, "value"), buildRelaxedConeMap(dropped));
    test::GpuConeMapCheck conservative;
    conservative.add("bundled", bundled.width, pageConeMap(page.at(6, "value")),
                     buildConservativeConeMap(bundled));
    conservative.add("noise37", dropped.width, pageConeMap(page.at(18, "value")),
                     buildConservativeConeMap(dropped));
    std::printf("    the page's GPU cone maps: %s\n", conservative.summary().c_str());
    EXPECT_EQ(conservative.wrong, 0u) << testing::PrintToString(conservative.firstWrong);
    EXPECT_GE(double(conservative.same), 0.9 * double(conservative.texels));

    const std::string line = page.at(19, "value");
    EXPECT_NE(line.find("cone's conservative cone map built on the GPU in "), std::string::npos)
        << line;
    EXPECT_NE(line.find("rcsm's relaxed cone map built in WebAssembly in "), std::string::npos)
        << line;
    // The new map's relaxed build went row by row: each of its 23 rows is more than a whole
    // percent, so the worker posted every one, 1/23 to 1, and the panel heard them in order.
    std::istringstream reported(page.at(20, "value"));
    std::vector<double> fractions{std::istream_iterator<double>(reported), {}};
    ASSERT_EQ(fractions.size(), 23u) << page.at(20, "value");
    for (std::size_t k = 0; k < fractions.size(); ++k)
        EXPECT_DOUBLE_EQ(fractions[k], double(k + 1) / 23) << "report " << k;
}

// The page's GPU build of cone's map on the adversarial maps the programs' GPU build is
// held to (test::coneCases: spikes, walls, heights from 1e-22 to 1e3, a base 3000 high)
// and a rough 96 x 80 noise, given to the page's renderer as floats (a PNG would quantise
// them; ReliefRenderer.setMap, then addConservativeConeMap as the page calls it):
// SwiftShader's float arithmetic, not Mesa's, under the same promise
// (test::GpuConeMapCheck). Every other map with maxmip's quadtree made beforehand: the
// build keeps a quadtree the map had and drops one it made.
TEST_F(WebPage, GpuConeMapIsTheCppMapOrNarrowerInTheBrowser) {
    std::vector<test::ConeCase> cases = test::coneCases();
    cases.push_back({"noise 96x80", synth::valueNoise(96, 80, 3.0, 3, 28)});
    std::string maps = "[";
    for (const test::ConeCase& c : cases) {
        char number[32];
        maps += (maps.size() > 1 ? ", [" : "[") + std::to_string(c.map.width) + ", " +
                std::to_string(c.map.height) + ", [";
        for (std::size_t k = 0; k < c.map.samples.size(); ++k) {
            std::snprintf(number, sizeof number, "%s%.9g", k ? ", " : "", c.map.samples[k]);
            maps += number;
        }
        maps += "]]";
    }
    maps += "]";
    // Each map made the renderer's, its cone map drawn and read back, with whether the
    // quadtree is there after: "kept" or "dropped", a colon, the texels.
    const std::string build =
        "(async () => { const r = microrelief.renderer, out = []; let k = 0;"
        " for (const [width, height, samples] of " +
        maps +
        ") {"
        "  r.setMap(new Float32Array(samples), width, height, false, k++ % 2 === 1);"
        "  if (!await r.addConservativeConeMap()) throw new Error('no cone map');"
        "  out.push((r.textures.aligned ? 'kept:' : 'dropped:') +"
        "   Array.from(r.textures.readConeMap('conservative')).join(' ')); }"
        " return out.join(';'); })()";
    const PageRun page = evalOnReadyPage(build);
    ASSERT_EQ(page.at(1, "state"), "ready") << page.at(1, "error");
    std::istringstream results(page.at(2, "value"));
    test::GpuConeMapCheck check;
    std::string result;
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const test::ConeCase& c = cases[k];
        ASSERT_TRUE(std::getline(results, result, ';')) << c.name << ": no result" << page.err;
        const std::size_t colon = result.find(':');
        ASSERT_NE(colon, std::string::npos) << c.name << ": " << result.substr(0, 80);
        EXPECT_EQ(result.substr(0, colon), k % 2 == 1 ? "kept" : "dropped")
            << c.name << ": maxmip's quadtree after the build";
        check.add(c.name, c.map.width, pageConeMap(result.substr(colon + 1)),
                  buildConservativeConeMap(c.map));
    }
    std::printf("    the page's GPU cone maps: %s\n", check.summary().c_str());
    EXPECT_EQ(check.wrong, 0u) << testing::PrintToString(check.firstWrong);
    EXPECT_GE(double(check.same), 0.9 * double(check.texels));
}

}  // namespace
