// microrelief-make-map and microrelief-bench as a user meets them: sizes and output
// folders refused before any work (issue 15), with the spec's one-line failure.
#include <gtest/gtest.h>

#include <sstream>

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

    const test::RunResult ok = run(MICRORELIEF_MAKE_MAP_EXE, "noise --size 5x3" + out);
    ASSERT_EQ(ok.status, 0) << ok.err;
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
    EXPECT_FALSE(std::filesystem::exists(dir / "b"));
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

}  // namespace
