// microrelief-make-map, microrelief-bench and microrelief-glsl-bundle as a user meets
// them: sizes and output folders refused before any work (issue 15), includes from
// outside the root (issue 25), with the spec's one-line failure.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <OpenImageIO/imageio.h>

#include "TestSupport.h"

using namespace microrelief;

namespace {

class ToolsCli : public ::testing::Test {
protected:
    test::RunResult run(const char* program, const std::string& args) {
        return test::runCommand(std::string(program) + " " + args, dir.path());
    }
    test::ScratchDir dir;
};

// An 8-bit PNG of `channels` interleaved channels.
void writePng(const std::filesystem::path& file, int width, int height, int channels,
              const std::vector<std::uint8_t>& pixels) {
    auto out = OIIO::ImageOutput::create("png");
    ASSERT_TRUE(out);
    ASSERT_TRUE(
        out->open(file.string(), OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
}

// bench.csv's rows, the header first, each split into its fields (the renderer's name is
// the one quoted field, which may hold commas).
std::vector<std::vector<std::string>> readBenchCsv(const std::filesystem::path& file) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream csv(test::readText(file));
    for (std::string line; std::getline(csv, line);) {
        std::vector<std::string> f;
        std::istringstream fields(line);
        for (std::string v; std::getline(fields, v, ',');) {
            if (!f.empty() && std::count(f.back().begin(), f.back().end(), '"') % 2 == 1)
                f.back() += "," + v;
            else
                f.push_back(v);
        }
        if (!line.empty() && line.back() == ',') f.emplace_back();  // getline drops it
        rows.push_back(f);
    }
    return rows;
}

TEST_F(ToolsCli, MakeMapRefusesMalformedAndOversizedSizes) {
    const std::string out = " --out " + (dir / "m.png").string();
    for (const char* size : {"5x5junk", "5x5.5", "+5x5", "5x", "x5", "0x5", "5", "-5x5"}) {
        const test::RunResult r =
            run(MICRORELIEF_MAKE_MAP_EXE, std::string("noise --size '") + size + "'" + out);
        test::expectOneLineFailure(r, "microrelief-make-map", 2, size);
    }
    // Beyond the largest map the programs load: refused before 40 GB of noise is made.
    for (const char* size : {"100000x100000", "46341x46341", "16385x1"}) {
        const test::RunResult r =
            run(MICRORELIEF_MAKE_MAP_EXE, std::string("noise --size ") + size + out);
        test::expectOneLineFailure(r, "microrelief-make-map", 2, "larger than 16384 x 16384");
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "m.png"));

    // The albedo's size under its own flag, and never without the albedo it sizes.
    test::expectOneLineFailure(
        run(MICRORELIEF_MAKE_MAP_EXE, "cobbles --albedo a.png --albedo-size 0x0" + out),
        "microrelief-make-map", 2, "--albedo-size expects WIDTHxHEIGHT");
    test::expectOneLineFailure(
        run(MICRORELIEF_MAKE_MAP_EXE, "cobbles --albedo a.png --albedo-size 99999x10" + out),
        "microrelief-make-map", 2, "--albedo-size 99999x10 is larger than 16384");
    test::expectOneLineFailure(run(MICRORELIEF_MAKE_MAP_EXE, "noise --albedo-size 8x8" + out),
                               "microrelief-make-map", 2, "--albedo-size needs --albedo");
    test::expectOneLineFailure(run(MICRORELIEF_MAKE_MAP_EXE, "noise --seed -1" + out),
                               "microrelief-make-map", 2, "--seed: '-1' is not a value it takes");
    EXPECT_FALSE(std::filesystem::exists(dir / "m.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    for (const char* program : {MICRORELIEF_MAKE_MAP_EXE, MICRORELIEF_BENCH_EXE}) {
        const test::RunResult version = run(program, "--version");
        EXPECT_EQ(version.status, 0) << program << ": " << version.err;
        const std::string name = std::filesystem::path(program).filename().string();
        EXPECT_EQ(version.out.rfind(name + " ", 0), 0u) << version.out;
    }

    const test::RunResult ok = run(MICRORELIEF_MAKE_MAP_EXE, "noise --size 5x3" + out);
    ASSERT_EQ(ok.status, 0) << ok.err;
    EXPECT_NE(ok.out.find("wrote"), std::string::npos) << ok.out;
    // -q as render takes it: nothing printed on success.
    const test::RunResult quiet = run(MICRORELIEF_MAKE_MAP_EXE, "noise -q --size 5x3" + out);
    ASSERT_EQ(quiet.status, 0) << quiet.err;
    EXPECT_EQ(quiet.out + quiet.err, "");
    EXPECT_EQ(ok.out.find("8 bits"), std::string::npos) << ok.out;
    // A format that keeps 8 bits a sample (as its header says) is written, and said.
    const test::RunResult jpeg =
        run(MICRORELIEF_MAKE_MAP_EXE, "noise --size 5x3 --out " + (dir / "m.jpg").string());
    ASSERT_EQ(jpeg.status, 0) << jpeg.err;
    EXPECT_NE(jpeg.out.find("(noise, 5x3, heights in 8 bits, lossy: .png or .tif keep 16"),
              std::string::npos)
        << jpeg.out;
    auto image = OIIO::ImageInput::open((dir / "m.png").string());
    ASSERT_TRUE(image);
    EXPECT_EQ(image->spec().width, 5);
    EXPECT_EQ(image->spec().height, 3);
}

TEST_F(ToolsCli, BenchRefusesUnwritableOutputFoldersAndEmptyMethodsBeforeAnyWork) {
    test::writeBytes(dir / "file.txt", {'x'});
    auto expectRefused = [&](const std::string& args, const std::string& mentions) {
        const test::RunResult r = run(MICRORELIEF_BENCH_EXE, "--quick " + args);
        test::expectOneLineFailure(r, "microrelief-bench", 2, mentions);
        // Nothing started: the first thing the benchmark prints is the map it makes.
        EXPECT_EQ(r.out, "") << args;
    };
    expectRefused("--out-dir /dev/full", "/dev/full is not a folder");
    expectRefused("--out-dir " + (dir / "file.txt").string(), "file.txt is not a folder");
    expectRefused("--out-dir " + (dir / "file.txt" / "sub").string(), "is not a folder");
    expectRefused("--methods '' --out-dir " + (dir / "b").string(), "--methods names no method");
    expectRefused("--methods multilevel,,maxmip --out-dir " + (dir / "b").string(), "--method");
    expectRefused("--bases '' --out-dir " + (dir / "b").string(), "--bases names no base");
    expectRefused("--interpolations '' --out-dir " + (dir / "b").string(),
                  "--interpolations names no interpolation");
    // Unknown items, named with the list flag the user gave.
    expectRefused("--methods foo --out-dir " + (dir / "b").string(), "unknown --methods 'foo'");
    expectRefused("--bases torus --out-dir " + (dir / "b").string(), "unknown --bases 'torus'");
    expectRefused("--interpolations bicubic --out-dir " + (dir / "b").string(),
                  "unknown --interpolations 'bicubic'");
    // The tables' clock, one of four (Report.h: Clock).
    expectRefused("--clock gpu --out-dir " + (dir / "b").string(),
                  "--clock: 'gpu' is not one of auto, timer, wall, cpu");
    // Views and the relief's sides: whole numbers in range, one clear line each.
    expectRefused("--views 95 --out-dir " + (dir / "b").string(), "--views: '95' is not a whole number");
    expectRefused("--views '' --out-dir " + (dir / "b").string(), "--views names no view");
    expectRefused("--map-sizes abc --out-dir " + (dir / "b").string(), "--map-sizes: 'abc'");
    // A list that names an item twice (its rows would merge), and nothing to measure at all.
    expectRefused("--views 30,60,30 --out-dir " + (dir / "b").string(), "--views names 30 twice");
    // An empty item, trailing too (it was read as '--views 30'), is refused as itself.
    expectRefused("--views 30, --out-dir " + (dir / "b").string(),
                  "--views: '' is not a whole number from 0 to 89");
    expectRefused("--methods cone, --out-dir " + (dir / "b").string(), "unknown --methods ''");
    expectRefused("--maps nope.png, --out-dir " + (dir / "b").string(),
                  "--maps '': an empty file name");
    expectRefused("--map-sizes 64,64 --out-dir " + (dir / "b").string(),
                  "--map-sizes names 64 twice");
    expectRefused("--methods cone,maxmip,cone --out-dir " + (dir / "b").string(),
                  "--methods names cone twice");
    expectRefused("--interpolations bilinear,bilinear --out-dir " + (dir / "b").string(),
                  "--interpolations names bilinear twice");
    expectRefused("--maps '' --map-sizes 0 --out-dir " + (dir / "b").string(),
                  "nothing to measure: no map");
    // The coarse pass's tiles: 2 to 64 (ReliefRenderer::setCoarsePass), each once, 0 alone.
    expectRefused("--coarse-tiles 1 --out-dir " + (dir / "b").string(),
                  "--coarse-tiles: '1' is not a whole number from 2 to 64");
    expectRefused("--coarse-tiles 8,65 --out-dir " + (dir / "b").string(),
                  "--coarse-tiles: '65' is not a whole number from 2 to 64");
    expectRefused("--coarse-tiles 8,8 --out-dir " + (dir / "b").string(),
                  "--coarse-tiles names 8 twice");
    // Maps: a missing file named, before any relief is made; 'fetched' with no list of
    // fetched maps (none under this scratch folder, the working folder here, whatever the
    // environment says) names the list it looked for.
    expectRefused("--maps nope.png --out-dir " + (dir / "b").string(), "nope.png: no such file");
    const test::RunResult noList = test::runCommand(
        "cd " + dir.path().string() +
            " && env -u MICRORELIEF_BENCH_MAPS " MICRORELIEF_BENCH_EXE " --quick --maps fetched",
        dir.path());
    test::expectOneLineFailure(noList, "microrelief-bench", 2,
                               "out/bench-maps/maps.txt: no list of fetched maps");
    // FILE[:CHANNEL][:normalize]: a channel the image lacks is the loader's refusal, named
    // with the entry; a channel no map has, an empty file name and suffixes on the list of
    // fetched maps are refused as they are read.
    writePng(dir / "grey.png", 2, 2, 1, {0, 1, 2, 3});
    const std::string grey = (dir / "grey.png").string();
    expectRefused("--maps " + grey + ":2 --out-dir " + (dir / "b").string(),
                  "--maps '" + grey + ":2': " + grey +
                      ": channel 2 is out of range; the image has 1 channel(s)");
    expectRefused("--maps " + grey + ":1:normalize --out-dir " + (dir / "b").string(),
                  "channel 1 is out of range");
    expectRefused("--maps " + grey + ":1024 --out-dir " + (dir / "b").string(),
                  "--maps '" + grey + ":1024': channel 1024 is beyond the 1024 channels");
    expectRefused("--maps " + grey + ",,default --out-dir " + (dir / "b").string(),
                  "--maps '': an empty file name");
    expectRefused("--maps :normalize --out-dir " + (dir / "b").string(),
                  "--maps ':normalize': an empty file name");
    expectRefused("--maps fetched:1 --out-dir " + (dir / "b").string(),
                  "--maps 'fetched:1': 'fetched' names a list of maps");
    // Not a suffix: the whole text is the file's name.
    expectRefused("--maps " + grey + ":+1 --out-dir " + (dir / "b").string(),
                  grey + ":+1: no such file");
    // Two entries the report would name alike, whose rows would merge: a file of another
    // folder with the same stem, and a file named as the procedural relief.
    std::filesystem::create_directory(dir / "other");
    writePng(dir / "other" / "grey.png", 2, 2, 1, {0, 1, 2, 3});
    writePng(dir / "relief.png", 2, 2, 1, {0, 1, 2, 3});
    expectRefused("--maps " + grey + "," + (dir / "other" / "grey.png").string() + " --out-dir " +
                      (dir / "b").string(),
                  "--maps '" + (dir / "other" / "grey.png").string() +
                      "': the report would name it 'grey', as it names --maps '" + grey + "'");
    expectRefused("--maps " + (dir / "relief.png").string() + " --out-dir " + (dir / "b").string(),
                  "the report would name it 'relief', as it names the procedural relief");
    EXPECT_FALSE(std::filesystem::exists(dir / "b"));
}

// The comparisons beside the equal-accuracy table: equal-time accuracy, throughput with
// the fetches split into the traversal's reads of its bounds and the samples', and each
// method's memory and preprocessing, in the CSV and bench.md. What the figures are is the
// benchmark's business; here that each column holds what it says, on a 16 x 16 map.
TEST_F(ToolsCli, BenchReportsEqualTimeAccuracyFetchSplitAndCosts) {
    {
        // A ramp with a ridge: something for every method to hit.
        std::vector<std::uint8_t> pixels(16 * 16);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) pixels[y * 16 + x] = x == 8 ? 255 : 10 * x;
        auto out = OIIO::ImageOutput::create("map.png");
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open((dir / "map.png").string(),
                              OIIO::ImageSpec(16, 16, 1, OIIO::TypeDesc::UINT8)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
        out->close();
    }
    const test::RunResult r =
        run(MICRORELIEF_BENCH_EXE, "--maps " + (dir / "map.png").string() +
                                       " --map-sizes 0 --views 45 --size 24x24 --bases plane "
                                       "--interpolations bilinear,biquadratic --methods "
                                       "multilevel,maxmip,cone,relief --out-dir " +
                                       (dir / "b").string());
    ASSERT_EQ(r.status, 0) << r.err;
    // What was asked for and not measured is said, on the console and in bench.md: the
    // biquadratic level's rows are the exact methods' only.
    EXPECT_NE(r.err.find("microrelief-bench: not measured: relief: not on the biquadratic level"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(r.err.find("not measured: cone"), std::string::npos) << r.err;
    const std::vector<std::vector<std::string>> rows = readBenchCsv(dir / "b" / "bench.csv");
    ASSERT_GE(rows.size(), 2u);
    const std::vector<std::string>& header = rows.front();
    const auto column = [&](const std::string& name) {
        const auto at = std::find(header.begin(), header.end(), name);
        EXPECT_NE(at, header.end()) << name << " not in the header";
        return static_cast<std::size_t>(at - header.begin());
    };
    const std::size_t method = column("method"), fetches = column("fetches_mean"),
                      bounds = column("fetches_bounds_mean"), bytes = column("bytes_per_texel"),
                      where = column("preprocess_where"), mpix = column("mpix_per_s"),
                      p99 = column("p99_error_texels"), cpuBuild = column("preprocess_cpu_ms"),
                      param = column("param"), pass = column("coarse_fetches_mean"),
                      map = column("map"), off = column("off_half_texel_pct");
    std::set<std::string> seen;
    // The coarse pass's row (the default --coarse-tiles 8) beside the exact one on the
    // plane, bilinear and biquadratic: as exact (off % the same), its own reads counted
    // among the pixels' fetches and bounds; no other row has any.
    std::map<std::string, std::vector<std::string>> exactRows, coarseRows;
    for (std::size_t row = 1; row < rows.size(); ++row) {
        const std::vector<std::string>& f = rows[row];
        ASSERT_EQ(f.size(), header.size()) << "row " << row;
        const std::string m = f[method];
        seen.insert(m);
        SCOPED_TRACE("row " + std::to_string(row) + ", " + m);
        EXPECT_GT(std::stod(f[mpix]), 0.0);
        EXPECT_GE(std::stod(f[p99]), 0.0);
        // Samples R32F, 4 bytes a texel; the windows and maxmip's quadtree R16F mip chains
        // (2 x 4/3 for a 16 x 16 map); cone's map RG16F, 4.
        if (f[param] == "exact+coarse8") {
            coarseRows[f[map]] = f;
            EXPECT_GT(std::stod(f[pass]), 0.0);
            EXPECT_LE(std::stod(f[pass]), std::stod(f[bounds]));
        } else {
            EXPECT_EQ(std::stod(f[pass]), 0.0) << f[param];
        }
        if (m == "multilevel" && f[param] == "exact") exactRows[f[map]] = f;
        if (m == "multilevel" || m == "maxmip") {
            EXPECT_NEAR(std::stod(f[bytes]),
                        4.0 + 2.0 * (1.0 + 1 / 4. + 1 / 16. + 1 / 64. + 1 / 256.), 0.01);
            EXPECT_EQ(f[where], "gpu");
            EXPECT_EQ(f[cpuBuild], "");  // built on the GPU only
            // The traversal reads its bounds, the last level the samples.
            EXPECT_GT(std::stod(f[bounds]), 0.0);
            EXPECT_LT(std::stod(f[bounds]), std::stod(f[fetches]));
        } else if (m == "cone") {
            EXPECT_DOUBLE_EQ(std::stod(f[bytes]), 8.0);
            // Its cone map built on the GPU (what the frames read) and on the CPU.
            EXPECT_EQ(f[where], "gpu");
            EXPECT_GT(std::stod(f[cpuBuild]), 0.0);
            EXPECT_GT(std::stod(f[bounds]), 0.0);
        } else {
            EXPECT_EQ(m, "relief");
            EXPECT_DOUBLE_EQ(std::stod(f[bytes]), 4.0);
            EXPECT_EQ(f[where], "-");
            EXPECT_EQ(std::stod(f[bounds]), 0.0);  // no bounds: every read is a sample's
            EXPECT_GT(std::stod(f[fetches]), 0.0);
        }
    }
    EXPECT_EQ(seen, (std::set<std::string>{"multilevel", "maxmip", "cone", "relief"}));
    EXPECT_EQ(coarseRows.size(), 2u);  // map and map-biquadratic
    for (const auto& [name, row] : coarseRows) {
        ASSERT_EQ(exactRows.count(name), 1u) << name;
        EXPECT_EQ(row[off], exactRows[name][off]) << name;
    }
    const std::string md = test::readText(dir / "b" / "bench.md");
    for (const char* section : {"Equal-time accuracy",
                                "| map | size | view | method | setting | ms | Mpix/s | fetches | "
                                "bounds | samples |",
                                "| map | size | method | bytes / texel | preprocessing ms |",
                                "| map | 16 | cone | 8.00 |", " (gpu), ",
                                "Not measured:\n\n- relief: not on the biquadratic level",
                                "| map-biquadratic | 16 | 45° | cone | ",
                                "The coarse pass (`--coarse-tiles`)",
                                "| single ms | fetches | tile | ms | over single |"})
        EXPECT_NE(md.find(section), std::string::npos) << section;
    // Without the procedural relief there are no size targets, and no empty heading.
    EXPECT_EQ(md.find("Targets:"), std::string::npos);
}

// Maps and folders named with what CSV, gnuplot and the shell take as syntax (a space, a
// quote, a comma): bench.csv quotes the name that needs it, and the plots are drawn in such a
// folder (or, where gnuplot is not installed, the warning says so and nothing else fails).
TEST_F(ToolsCli, BenchWritesMapsAndFoldersNamedWithQuotesAndCommas) {
    const std::filesystem::path folder = dir / "a b's";
    std::filesystem::create_directory(folder);
    std::vector<std::uint8_t> ramp(16 * 16);
    for (int k = 0; k < 16 * 16; ++k) ramp[k] = static_cast<std::uint8_t>(12 * (k % 16));
    writePng(folder / "it's.png", 16, 16, 1, ramp);
    writePng(folder / "x,y.png", 16, 16, 1, ramp);
    std::ofstream(folder / "maps.txt") << "it's.png\nx,y.png\n";
    const test::RunResult r = test::runCommand(
        "MICRORELIEF_BENCH_MAPS=\"" + folder.string() +
            "\" " MICRORELIEF_BENCH_EXE
            " --maps fetched --map-sizes 0 --views 45 --size 16x16 --bases plane --interpolations "
            "bilinear --methods multilevel,relief --frames 10 --out-dir \"" +
            (folder / "out").string() + "\"",
        dir.path());
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::vector<std::string>> rows = readBenchCsv(folder / "out" / "bench.csv");
    ASSERT_GE(rows.size(), 2u);
    const std::size_t map = static_cast<std::size_t>(
        std::find(rows[0].begin(), rows[0].end(), "map") - rows[0].begin());
    std::set<std::string> maps;
    for (std::size_t k = 1; k < rows.size(); ++k) {
        ASSERT_EQ(rows[k].size(), rows[0].size()) << "row " << k;
        maps.insert(rows[k][map]);
    }
    EXPECT_EQ(maps, (std::set<std::string>{"it's", "\"x,y\""}));
    if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
        EXPECT_TRUE(std::filesystem::exists(folder / "out" / "pareto-it's-16.png")) << r.err;
        EXPECT_TRUE(std::filesystem::exists(folder / "out" / "pareto-x,y-16.png")) << r.err;
        EXPECT_EQ(r.err.find("no plots"), std::string::npos) << r.err;
    } else {
        EXPECT_NE(r.err.find("no plots: gnuplot is not installed"), std::string::npos) << r.err;
    }
}

// --maps FILE[:CHANNEL][:normalize] (issue 28), on the command line and on the lines of
// a fetched-map list: the channel and the normalisation reach the map that is measured, and
// the report keeps one file's entries apart. Each entry is held against a file holding
// what it should load: two.png's channel 1 is one:ch1.png (a name with a colon, whole),
// low.png's two levels normalised are full.png's 0 and 1. Times vary; the fetch counts and
// the covered area do not, and differ between different maps.
TEST_F(ToolsCli, BenchMapsTakeAChannelAndNormalisation) {
    const int n = 16;
    std::vector<std::uint8_t> two(n * n * 2), ch1(n * n), low(n * n), full(n * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const int i = y * n + x;
            const bool up = (x / 4 + y / 4) % 2 == 1;  // 4 x 4 blocks, a checkerboard
            two[2 * i] = x == 8 ? 255 : 10 * x;        // a ramp with a ridge
            two[2 * i + 1] = ch1[i] = up ? 200 : 30;
            low[i] = up ? 128 : 64;
            full[i] = up ? 255 : 0;
        }
    const std::filesystem::path fetched = dir / "fetched";
    std::filesystem::create_directories(fetched);
    writePng(fetched / "two.png", n, n, 2, two);
    writePng(dir / "one:ch1.png", n, n, 1, ch1);
    writePng(dir / "low.png", n, n, 1, low);
    writePng(dir / "full.png", n, n, 1, full);
    std::ofstream(fetched / "maps.txt") << "two.png\ntwo.png:1\n";
    const std::string maps = "fetched," + (dir / "one:ch1.png").string() + "," +
                             (dir / "low.png").string() + "," + (dir / "low.png").string() +
                             ":normalize," + (dir / "full.png").string();
    const test::RunResult r = test::runCommand(
        "MICRORELIEF_BENCH_MAPS=" + fetched.string() + " " MICRORELIEF_BENCH_EXE " --maps " + maps +
            " --map-sizes 0 --views 45 --size 24x24 --bases plane --interpolations bilinear "
            "--methods multilevel --out-dir " +
            (dir / "b").string(),
        dir.path());
    ASSERT_EQ(r.status, 0) << r.err;

    const std::vector<std::vector<std::string>> csv = readBenchCsv(dir / "b" / "bench.csv");
    ASSERT_FALSE(csv.empty());
    const std::vector<std::string>& header = csv.front();
    const auto column = [&](const std::string& name) {
        const auto at = std::find(header.begin(), header.end(), name);
        EXPECT_NE(at, header.end()) << name;
        return static_cast<std::size_t>(at - header.begin());
    };
    const std::size_t map = column("map"), param = column("param");
    const std::vector<std::size_t> figures{column("fetches_mean"), column("fetches_max"),
                                           column("fetches_bounds_mean"), column("hit_pct")};
    // (map, setting) -> the figures that depend on the heights alone.
    std::map<std::pair<std::string, std::string>, std::vector<std::string>> seen;
    for (std::size_t k = 1; k < csv.size(); ++k) {
        const std::vector<std::string>& f = csv[k];
        ASSERT_EQ(f.size(), header.size());
        std::vector<std::string> values;
        for (std::size_t c : figures) values.push_back(f.at(c));
        seen[{f[map], f[param]}] = values;
    }
    std::set<std::string> names;
    for (const auto& [key, values] : seen) names.insert(key.first);
    EXPECT_EQ(names,
              (std::set<std::string>{"two", "two:1", "one:ch1", "low", "low:normalize", "full"}));
    for (const char* setting : {"exact", "1px", "4px"}) {
        SCOPED_TRACE(setting);
        const auto at = [&](const char* name) { return seen[{name, setting}]; };
        ASSERT_FALSE(at("two:1").empty());
        EXPECT_EQ(at("two:1"), at("one:ch1"));
        EXPECT_NE(at("two:1"), at("two"));
        EXPECT_EQ(at("low:normalize"), at("full"));
        EXPECT_NE(at("low:normalize"), at("low"));
    }
    const std::string md = test::readText(dir / "b" / "bench.md");
    for (const char* name : {"| two:1 |", "| low:normalize |"})
        EXPECT_NE(md.find(name), std::string::npos) << name;
    // A Pareto plot for each of the six maps, named without the colons some file systems
    // refuse ("two:1" as pareto-two-1-N.png).
    if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
        std::set<std::string> plots;
        for (const auto& entry : std::filesystem::directory_iterator(dir / "b")) {
            const std::string name = entry.path().filename().string();
            if (name.rfind("pareto-", 0) == 0 && entry.path().extension() == ".png")
                plots.insert(name);
        }
        EXPECT_EQ(plots.size(), 6u);
        for (const std::string& plot : plots) EXPECT_EQ(plot.find(':'), std::string::npos) << plot;
        EXPECT_EQ(plots.count("pareto-two-1-" + std::to_string(n) + ".png"), 1u);
    }
}

// The default run measures the fetched maps beside the bundled one where there is a list of
// them; where there is none (the list's folder is relative to the working folder), that is
// said on the console and in bench.md, not left out unremarked. Seen red: nothing said.
TEST_F(ToolsCli, BenchSaysWhenTheDefaultRunFindsNoFetchedMaps) {
    const std::string measureLittle =
        " --map-sizes 0 --views 45 --size 16x16 --bases plane --interpolations bilinear "
        "--methods multilevel --frames 10 --out-dir b";
    const test::RunResult r = test::runCommand(
        "cd " + dir.path().string() + " && env -u MICRORELIEF_BENCH_MAPS " MICRORELIEF_BENCH_EXE +
            measureLittle,
        dir.path());
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string note =
        "the real maps scripts/bench-maps.sh fetches: no list at out/bench-maps/maps.txt "
        "(relative to the working folder; MICRORELIEF_BENCH_MAPS names another)";
    EXPECT_NE(r.err.find("microrelief-bench: not measured: " + note), std::string::npos) << r.err;
    EXPECT_NE(test::readText(dir / "b" / "bench.md").find("- " + note), std::string::npos);
    // A list the variable names that lists nothing: said so, not "no list".
    const std::string named = "cd " + dir.path().string() +
                              " && MICRORELIEF_BENCH_MAPS=" + dir.path().string() +
                              " " MICRORELIEF_BENCH_EXE + measureLittle;
    std::ofstream(dir / "maps.txt") << "\n";
    const test::RunResult empty = test::runCommand(named, dir.path());
    ASSERT_EQ(empty.status, 0) << empty.err;
    EXPECT_NE(empty.err.find("not measured: the real maps scripts/bench-maps.sh fetches: " +
                             (dir / "maps.txt").string() + " lists none\n"),
              std::string::npos)
        << empty.err;
    // With a list, its maps are measured and nothing is said of it.
    writePng(dir / "grey.png", 4, 4, 1, std::vector<std::uint8_t>(16, 100));
    std::ofstream(dir / "maps.txt") << "grey.png\n";
    const test::RunResult listed = test::runCommand(named, dir.path());
    ASSERT_EQ(listed.status, 0) << listed.err;
    EXPECT_EQ(listed.err.find("bench-maps.sh fetches"), std::string::npos) << listed.err;
    EXPECT_EQ(test::readText(dir / "b" / "bench.md").find("bench-maps.sh fetches"),
              std::string::npos);
    EXPECT_NE(test::readText(dir / "b" / "bench.csv").find("grey"), std::string::npos);
}

// A fetched-map list's line is read as --maps reads an entry: a bad one is refused naming
// the list, its line and the text.
TEST_F(ToolsCli, BenchRefusesABadLineOfTheFetchedMapList) {
    writePng(dir / "grey.png", 2, 2, 1, {0, 1, 2, 3});
    for (const auto& [line, mentions] : std::vector<std::pair<std::string, std::string>>{
             {"grey.png:3",
              "2: 'grey.png:3': " + (dir / "grey.png").string() + ": channel 3 is out of range"},
             {":normalize", "2: ':normalize': an empty file name"}}) {
        SCOPED_TRACE(line);
        std::ofstream(dir / "maps.txt") << "grey.png\n" << line << "\n";
        const test::RunResult r =
            test::runCommand("MICRORELIEF_BENCH_MAPS=" + dir.path().string() +
                                 " " MICRORELIEF_BENCH_EXE " --quick --maps fetched --out-dir " +
                                 (dir / "b").string(),
                             dir.path());
        test::expectOneLineFailure(
            r, "microrelief-bench", 2,
            "--maps fetched: " + (dir / "maps.txt").string() + ":" + mentions);
        EXPECT_EQ(r.out, "");
    }
    // A run that measures no map file does not read the list. Seen red: --rebuild refused
    // with the list's bad line.
    const test::RunResult rebuild =
        test::runCommand("MICRORELIEF_BENCH_MAPS=" + dir.path().string() +
                             " " MICRORELIEF_BENCH_EXE
                             " --rebuild --rebuild-sizes 16 --size 16x16 --frames 10 --out-dir " +
                             (dir / "r").string(),
                         dir.path());
    EXPECT_EQ(rebuild.status, 0) << rebuild.err;
}

// --rebuild (issue 16): rebuild.csv with a row per map size and the columns the issue
// names; bad size lists refused before any work. What the figures are is the benchmark's
// business: here only that they are there and are numbers.
TEST_F(ToolsCli, BenchRebuildWritesItsCsv) {
    const auto out = " --out-dir " + (dir / "r").string();
    for (const char* bad : {"''", "0", "abc", "64,,32"}) {
        const test::RunResult r =
            run(MICRORELIEF_BENCH_EXE, std::string("--rebuild --rebuild-sizes ") + bad + out);
        test::expectOneLineFailure(r, "microrelief-bench", 2, "--rebuild-sizes");
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "r"));
    const test::RunResult r =
        run(MICRORELIEF_BENCH_EXE, "--rebuild --rebuild-sizes 64,33 --size 48x40" + out);
    ASSERT_EQ(r.status, 0) << r.err;
    std::istringstream csv(test::readText(dir / "r" / "rebuild.csv"));
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("map_size,full_rebuild_ms,brush_update_ms,frame_trace_ms,renderer,", 0),
              0u)
        << header;
    std::vector<std::string> rows;
    while (std::getline(csv, line)) rows.push_back(line);
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].rfind("64,", 0), 0u);
    EXPECT_EQ(rows[1].rfind("33,", 0), 0u);
    for (const std::string& row : rows) {
        std::istringstream fields(row);
        std::string size, full, brush, frame;
        std::getline(fields, size, ',');
        std::getline(fields, full, ',');
        std::getline(fields, brush, ',');
        std::getline(fields, frame, ',');
        EXPECT_GT(std::stod(full), 0.0) << row;
        EXPECT_GT(std::stod(brush), 0.0) << row;
        EXPECT_GT(std::stod(frame), 0.0) << row;
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "r" / "rebuild.md"));
}

// --terrain (issue 29): a row per map size, path and view in terrain.csv, each size in
// whole textures, through pages from memory and from a pyramid file (removed after); the
// paged rows drew until exact, and every path agrees with the CPU reference on every
// pixel. Conflicting modes and empty lists refused first.
TEST_F(ToolsCli, BenchTerrainDrawsEachSizeWholeAndThroughPagesExactly) {
    const auto out = " --out-dir " + (dir / "t").string();
    for (const auto& [args, mentions] : std::vector<std::pair<std::string, std::string>>{
             {"--terrain --rebuild", "one at a time"},
             {"--terrain --map-sizes 0", "--map-sizes names no size"},
             {"--terrain --memory 0", "--memory"},
             {"--memory 64", "--memory is the page budget of --terrain"}}) {
        const test::RunResult r = run(MICRORELIEF_BENCH_EXE, args + out);
        test::expectOneLineFailure(r, "microrelief-bench", 2, mentions);
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "t"));
    const test::RunResult r =
        run(MICRORELIEF_BENCH_EXE, "--terrain --map-sizes 64,33 --views 45 --size 48x40" + out);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::vector<std::string>> csv = readBenchCsv(dir / "t" / "terrain.csv");
    ASSERT_EQ(csv.size(), 7u);  // the header, then 64 and 33: whole, paged, file
    const std::vector<std::string>& header = csv[0];
    const auto column = [&](const std::string& name) {
        const auto at = std::find(header.begin(), header.end(), name);
        EXPECT_NE(at, header.end()) << name;
        return static_cast<std::size_t>(at - header.begin());
    };
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"64", "whole"}, {"64", "paged"}, {"64", "file"},
        {"33", "whole"}, {"33", "paged"}, {"33", "file"}};
    for (std::size_t k = 0; k < expected.size(); ++k) {
        const std::vector<std::string>& row = csv[k + 1];
        ASSERT_EQ(row.size(), header.size());
        EXPECT_EQ(row[column("map_size")], expected[k].first);
        EXPECT_EQ(row[column("path")], expected[k].second);
        const bool paged = expected[k].second != "whole";
        // A paged picture takes a draw to find its pages and one that wants none.
        EXPECT_EQ(std::stoi(row[column("draws")]) >= 2, paged) << k;
        EXPECT_EQ(std::stod(row[column("pages_per_frame")]), 0.0) << k;  // all fit
        EXPECT_GT(std::stod(row[column("frame_ms")]), 0.0) << k;
        EXPECT_GT(std::stod(row[column("fetches_per_hit_pixel")]), 1.0) << k;
        EXPECT_EQ(std::stod(row[column("coverage_mismatch_pct")]), 0.0) << k;
        EXPECT_EQ(std::stod(row[column("off_half_texel_pct")]), 0.0) << k;
        EXPECT_EQ(std::stod(row[column("file_mib")]) > 0.0, expected[k].second == "file") << k;
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "t" / "terrain.md"));
    EXPECT_FALSE(std::filesystem::exists(dir / "t" / "terrain-pyramids")) << "files removed";
}

// The runs as subcommands (issue 49): each --help lists its own options only, a run takes
// no other run's option, an option before the subcommand's name (which the default run
// would take, and the subcommand lose) is refused in one line, and a subcommand runs as its
// old spelling does (rebuild --map-sizes as --rebuild --rebuild-sizes). Seen red: with the
// options before the name not refused, '--quick terrain --map-sizes 0' went on to run (and
// refused its empty list).
TEST_F(ToolsCli, BenchRunsAreSubcommandsEachWithItsOwnOptions) {
    const test::RunResult help = run(MICRORELIEF_BENCH_EXE, "--help");
    ASSERT_EQ(help.status, 0) << help.err;
    for (const char* subcommand : {"methods", "materials", "rebuild", "terrain", "mesh"})
        EXPECT_NE(help.out.find(std::string("\n  ") + subcommand + " "), std::string::npos)
            << subcommand << ": " << help.out;
    // Each run's --help: the options it takes, and none of another run's.
    for (const auto& [subcommand, takes, not_] :
         std::vector<std::tuple<std::string, std::string, std::string>>{
             {"methods", "--glsl330", "--memory"},
             {"materials", "--quick", "--map-sizes"},
             {"rebuild", "--map-sizes", "--views"},
             {"terrain", "--memory", "--maps"},
             {"mesh", "--grids", "--memory"}}) {
        const test::RunResult r = run(MICRORELIEF_BENCH_EXE, subcommand + " --help");
        ASSERT_EQ(r.status, 0) << subcommand << ": " << r.err;
        EXPECT_NE(r.out.find("microrelief-bench " + subcommand + " [OPTIONS]"), std::string::npos)
            << r.out;
        EXPECT_NE(r.out.find("  " + takes + " "), std::string::npos) << subcommand << r.out;
        EXPECT_EQ(r.out.find(not_), std::string::npos) << subcommand << r.out;
        EXPECT_EQ(r.out.find("--rebuild"), std::string::npos) << subcommand << r.out;
    }
    const auto out = " --out-dir " + (dir / "r").string();
    for (const auto& [args, mentions] : std::vector<std::pair<std::string, std::string>>{
             {"--quick terrain --map-sizes 0", "--quick comes before 'terrain'"},
             {"--terrain terrain --map-sizes 0", "--terrain comes before 'terrain'"},
             {"terrain --maps default", "--maps is not an option"},
             {"rebuild --quick", "--quick is not an option"},
             {"rebuild --map-sizes 64,,32", "--map-sizes: '' is not a map side"},
             {"terrain --memory 0", "--memory: '0' is not a whole number from 1 to 1048576"},
             {"terrain rebuild", "'rebuild' was not expected"}}) {
        const test::RunResult r = run(MICRORELIEF_BENCH_EXE, args + out);
        test::expectOneLineFailure(r, "microrelief-bench", 2, mentions);
        EXPECT_EQ(r.out, "") << args;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "r"));
    const test::RunResult r =
        run(MICRORELIEF_BENCH_EXE, "rebuild --map-sizes 33 --size 48x40 --frames 10" + out);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::vector<std::string>> csv = readBenchCsv(dir / "r" / "rebuild.csv");
    ASSERT_EQ(csv.size(), 2u);
    EXPECT_EQ(csv[1][0], "33");
    EXPECT_TRUE(std::filesystem::exists(dir / "r" / "rebuild.md"));
}

// mesh (issue 50): a row per mesh and view in mesh.csv, each mesh drawn on the same map,
// pixels and camera as the analytic base it copies; a flat grid is the plane exactly, so
// its picture agrees with the plane's on every pixel (the map made seamless: Mesh.cpp).
// Bad lists refused before any work. Seen red: with the map left as benchRelief gave it,
// the grid's row had 10 pixels hit by one picture only and a hit 0.63 texel off.
TEST_F(ToolsCli, BenchMeshDrawsEachMeshBesideItsBase) {
    const auto out = " --out-dir " + (dir / "m").string();
    for (const auto& [args, mentions] : std::vector<std::pair<std::string, std::string>>{
             {"mesh --grids 0 --tubes 0", "leave nothing to measure"},
             {"mesh --tubes 3", "--tubes: '3' is not a tube's sides"},
             {"mesh --grids 2,2", "--grids names 2 twice"},
             {"mesh --grids 2,,4", "--grids: '' is not"},
             {"mesh --map-size 1", "--map-size: 1 is not a map side"}}) {
        const test::RunResult r = run(MICRORELIEF_BENCH_EXE, args + out);
        test::expectOneLineFailure(r, "microrelief-bench", 2, mentions);
        EXPECT_EQ(r.out, "") << args;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "m"));
    const test::RunResult r = run(
        MICRORELIEF_BENCH_EXE,
        "mesh --size 40x32 --map-size 16 --grids 2 --tubes 8 --views 45 --frames 10" + out);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::vector<std::string>> csv = readBenchCsv(dir / "m" / "mesh.csv");
    ASSERT_EQ(csv.size(), 3u);  // the header, the grid, the tube
    const std::vector<std::string>& header = csv[0];
    const auto column = [&](const std::string& name) {
        const auto at = std::find(header.begin(), header.end(), name);
        EXPECT_NE(at, header.end()) << name;
        return static_cast<std::size_t>(at - header.begin());
    };
    const std::vector<std::string>& grid = csv[1];
    const std::vector<std::string>& tube = csv[2];
    EXPECT_EQ(grid[column("base")], "plane");
    EXPECT_EQ(grid[column("mesh")], "grid 2x2");
    EXPECT_EQ(grid[column("triangles")], "8");
    EXPECT_EQ(tube[column("base")], "cylinder");
    EXPECT_EQ(tube[column("mesh")], "tube 8x2");
    EXPECT_EQ(tube[column("triangles")], "32");
    for (const std::vector<std::string>& row : {grid, tube}) {
        ASSERT_EQ(row.size(), header.size());
        EXPECT_GT(std::stod(row[column("base_ms")]), 0.0);
        EXPECT_GT(std::stod(row[column("mesh_ms")]), 0.0);
        EXPECT_GT(std::stod(row[column("base_fetches_per_pixel")]), 0.0);
        EXPECT_GT(std::stod(row[column("mesh_fetches_per_pixel")]), 0.0);
        EXPECT_GT(std::stoi(row[column("base_hits")]), 40 * 32 / 10);
    }
    EXPECT_EQ(grid[column("hit_miss")], "0");
    // The two shaders' float rounding (the mesh's pieces in t, the plane's frame ray).
    EXPECT_LT(std::stod(grid[column("offset_max_texels")]), 0.05);
    EXPECT_TRUE(std::filesystem::exists(dir / "m" / "mesh.md"));
}

}  // namespace

// microrelief-glsl-bundle's includes (issue 25): only regular files inside the root (or a
// search folder), named relative to it, are spliced. Each hostile include is refused in
// one line naming the including file, its line and the reason: a device that never ends,
// a FIFO that never opens for writing (under `timeout`, so a hang fails rather than
// stalls), paths out of the root by "..", by an absolute name or by a link, a folder,
// include forms the bundler does not take, a file larger than a shader.
TEST_F(ToolsCli, GlslBundleSplicesOnlyRegularFilesInsideTheRoot) {
    const std::filesystem::path root = dir / "root";
    std::filesystem::create_directories(root / "sub");
    std::filesystem::create_directories(root / "lib");
    const auto write = [](const std::filesystem::path& file, const std::string& text) {
        std::ofstream(file, std::ios::binary) << text;
    };
    write(dir / "outside.glsl", "float secretOutside;\n");
    write(root / "lib/a.glsl", "float fromA;\n");
    write(root / "sub/inner.glsl", "#include \"../lib/a.glsl\"\nfloat fromInner;\n");
    ASSERT_EQ(::mkfifo((root / "fifo.glsl").c_str(), 0600), 0);
    std::filesystem::create_symlink("../outside.glsl", root / "out-link.glsl");
    std::filesystem::create_symlink("/dev/zero", root / "zero-link.glsl");
    std::filesystem::create_symlink("fifo.glsl", root / "fifo-link.glsl");
    {
        std::ofstream(root / "big.glsl") << "// big\n";
        std::filesystem::resize_file(root / "big.glsl", (4 << 20) + 1);  // sparse: no 4 MB written
    }
    const auto bundle = [&](const std::string& include) {
        write(root / "main.glsl", "// main\n" + include + "\nvoid main() {}\n");
        return run("timeout 20 " MICRORELIEF_GLSL_BUNDLE_EXE,
                   (root / "main.glsl").string() + " --root " + root.string());
    };

    const test::RunResult good = bundle("#include \"sub/inner.glsl\"");
    ASSERT_EQ(good.status, 0) << good.err;
    EXPECT_NE(good.out.find("float fromA;"), std::string::npos);  // "../" within the root
    EXPECT_NE(good.out.find("float fromInner;"), std::string::npos);

    const struct {
        std::string include, reason;
    } cases[] = {
        {"#include \"/dev/zero\"", "an absolute path"},
        {"#include \"" + (dir / "outside.glsl").string() + "\"", "an absolute path"},
        {"#include \"../../../../../../../../etc/passwd\"", "is outside the shader folders"},
        {"#include \"../outside.glsl\"", "is outside the shader folders"},
        {"#include \"sub/../../outside.glsl\"", "is outside the shader folders"},
        {"#include \"out-link.glsl\"", "is outside the shader folders"},
        {"#include \"zero-link.glsl\"", "is outside the shader folders"},
        {"#include \"fifo.glsl\"", "not a regular file"},
        {"#include \"fifo-link.glsl\"", "not a regular file"},
        {"#include \"sub\"", "a folder, not a file"},
        {"#include \".\"", "a folder, not a file"},
        {"#include \"big.glsl\"", "more than the 4194304 bytes"},
        {"#include \"nope.glsl\"", "not found"},
        {"#include \"lib/a.glsl", "quote is not closed"},
        {"#include <lib/a.glsl>", "#include <...> is not resolved here"},
        {"#include lib/a.glsl", "expected #include \"file\""},
        {"  #  include \"lib/a.glsl\" junk", "text after the file name"},
        {"#include \"\"", "an empty file name"},
        {"#include \"a\rb\x01.glsl\"", "control characters"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.include);
        const test::RunResult r = bundle(c.include);
        test::expectOneLineFailure(r, "microrelief-glsl-bundle", 2, "main.glsl:2: #");
        EXPECT_NE(r.err.find(c.reason), std::string::npos) << r.err;
        EXPECT_EQ(r.out, "");
        EXPECT_EQ(r.err.find('\r'), std::string::npos) << "a raw CR in the message";
        EXPECT_EQ(r.err.find('\x01'), std::string::npos) << "a raw control character";
    }
    // The file to bundle itself: a FIFO or a folder is refused without waiting on it.
    for (const char* file : {"fifo.glsl", "sub"}) {
        const test::RunResult r = run("timeout 20 " MICRORELIEF_GLSL_BUNDLE_EXE,
                                      (root / file).string() + " --root " + root.string());
        test::expectOneLineFailure(r, "microrelief-glsl-bundle", 2, "not a regular file");
    }
    test::expectOneLineFailure(run(MICRORELIEF_GLSL_BUNDLE_EXE, (root / "nowhere.glsl").string()),
                               "microrelief-glsl-bundle", 2, "nowhere.glsl: no such file");
    // A bad command line: one line and status 2, as for the other programs.
    test::expectOneLineFailure(run(MICRORELIEF_GLSL_BUNDLE_EXE, ""), "microrelief-glsl-bundle", 2,
                               "is required (see --help)");
    const test::RunResult elsewhere = run(
        MICRORELIEF_GLSL_BUNDLE_EXE, (dir / "outside.glsl").string() + " --root " + root.string());
    test::expectOneLineFailure(elsewhere, "microrelief-glsl-bundle", 2, "not inside the root");
}

// microrelief-glsl-bundle -I DIR (repeatable): an include is looked for in the including
// file's folder first, then in each -I folder in the order given; a spliced file's own
// includes likewise. A -I that is not a folder (a file, a missing path) is one error line
// and exit status 2, before anything is read.
TEST_F(ToolsCli, GlslBundleSearchesIncludeFoldersAfterTheFilesOwn) {
    const auto write = [](const std::filesystem::path& file, const std::string& text) {
        std::filesystem::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary) << text;
    };
    const std::filesystem::path project = dir / "project", first = dir / "first",
                                second = dir / "second";
    write(project / "main.glsl",
          "#include \"local.glsl\"\n#include \"lib/only_in_second.glsl\"\n"
          "#include \"both.glsl\"\nvoid main() {}\n");
    write(project / "local.glsl", "float fromProject;\n");
    write(first / "local.glsl", "float localFromFirst;\n");  // the file's own folder wins
    write(first / "both.glsl", "float bothFromFirst;\n");
    write(second / "both.glsl", "float bothFromSecond;\n");  // the first -I wins
    write(second / "lib/only_in_second.glsl", "#include \"helper.glsl\"\nfloat fromSecond;\n");
    write(second / "lib/helper.glsl", "float helperBesideIt;\n");  // its own folder first

    const std::string file = (project / "main.glsl").string();
    const test::RunResult good = run(MICRORELIEF_GLSL_BUNDLE_EXE,
                                     file + " -I " + first.string() + " -I " + second.string());
    ASSERT_EQ(good.status, 0) << good.err;
    for (const char* expected :
         {"float fromProject;", "float bothFromFirst;", "float fromSecond;", "float helperBesideIt;"})
        EXPECT_NE(good.out.find(expected), std::string::npos) << expected << "\n" << good.out;
    for (const char* unexpected : {"float localFromFirst;", "float bothFromSecond;"})
        EXPECT_EQ(good.out.find(unexpected), std::string::npos) << unexpected << "\n" << good.out;
    // The order of the -I folders decides.
    const test::RunResult swapped = run(MICRORELIEF_GLSL_BUNDLE_EXE,
                                        file + " -I " + second.string() + " -I " + first.string());
    ASSERT_EQ(swapped.status, 0) << swapped.err;
    EXPECT_NE(swapped.out.find("float bothFromSecond;"), std::string::npos) << swapped.out;
    // Without -I the include is not found: one error naming it.
    const test::RunResult without = run(MICRORELIEF_GLSL_BUNDLE_EXE, file);
    test::expectOneLineFailure(without, "microrelief-glsl-bundle", 2, "not found");
    // A -I that is not a folder.
    for (const std::filesystem::path& bad : {project / "local.glsl", dir / "missing"}) {
        SCOPED_TRACE(bad.string());
        const test::RunResult r =
            run(MICRORELIEF_GLSL_BUNDLE_EXE, file + " -I " + first.string() + " -I " + bad.string());
        test::expectOneLineFailure(r, "microrelief-glsl-bundle", 2, "not a directory");
        EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
        EXPECT_EQ(r.out, "");
    }
}
