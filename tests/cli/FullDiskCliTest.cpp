// The programs on a full disk and over paths they must not write (issue 25): every
// program and format fails with one line and exit 1, the old file intact byte for byte and
// no temporary left; a folder or FIFO at the target is refused before any work; a user's
// "<out>.tmp" is never touched. A full disk without privileges: a file size limit
// (RLIMIT_FSIZE, `ulimit -f`) smaller than the output, so the output's writes fail with
// EFBIG part-way as they would with ENOSPC. Each case first writes the same output without
// the limit, to show that it is larger than the limit (or the case would prove nothing).
#include <gtest/gtest.h>

#include <sys/stat.h>

#include "TestSupport.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

// Smaller than every output below; stdout and stderr, also files, stay far below it.
constexpr std::uint64_t kLimit = 4096;

// Without a GL backend: a run that reaches rendering fails with "no GL backend", so a
// refusal seen under it came before any rendering.
const std::string kNoGl =
    "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json MICRORELIEF_OSMESA_LIBRARY=/nonexistent.so ";

const std::vector<std::uint8_t> kOld = {'o', 'l', 'd', ' ', 'f', 'i', 'l', 'e', '\n'};

class FullDisk : public ::testing::Test {
protected:
    test::RunResult run(const std::string& command) {
        return test::runCommand(command, dir.path());
    }
    test::RunResult runLimited(const std::string& command, std::uint64_t bytes = kLimit) {
        return test::runCommandWithFileSizeLimit(command, bytes);
    }

    // Writes kOld at `file`, runs `command` under the limit, and checks the failure: one
    // line naming the file and the reason, exit 1, the old file as it was, nothing left.
    void expectFailsWhole(const std::string& program, const std::string& command,
                          const std::filesystem::path& file, std::uint64_t bytes = kLimit) {
        test::writeBytes(file, kOld);
        const test::RunResult r = runLimited(command, bytes);
        test::expectOneLineFailure(r, program, 1,
                                   file.string() + ": cannot write (File too large)");
        EXPECT_EQ(r.out.find("wrote"), std::string::npos) << r.out;
        EXPECT_EQ(test::readBytes(file), kOld) << file;
        EXPECT_EQ(test::hiddenFilesIn(file.parent_path()), std::vector<std::string>{});
    }

    // The premise: without the limit the output is written and larger than the limit.
    void expectLargerThanTheLimit(const std::string& command, const std::filesystem::path& file,
                                  std::uint64_t bytes = kLimit) {
        const test::RunResult r = run(command);
        ASSERT_EQ(r.status, 0) << r.err;
        ASSERT_GT(std::filesystem::file_size(file), bytes) << file;
    }

    test::ScratchDir dir;
    const std::string render = std::string(MICRORELIEF_RENDER_EXE) + " --size 160x120 ";
};

TEST_F(FullDisk, RenderFailsWholeInEveryFormat) {
    std::filesystem::create_directory(dir / "out");
    for (const char* extension : {"png", "bmp", "tga", "jpg", "tif", "exr"}) {
        SCOPED_TRACE(extension);
        const auto whole = dir / (std::string("whole.") + extension),
                   file = dir / "out" / (std::string("view.") + extension);
        expectLargerThanTheLimit(render + "--out " + whole.string(), whole);
        expectFailsWhole("microrelief-render", render + "--out " + file.string(), file);
    }
}

// The picture fits under the limit, the AOV does not: the pair is written together, so
// the picture is not replaced either.
TEST_F(FullDisk, RenderAovFailsAndThePictureStaysOld) {
    const auto picture = dir / "p.png", aov = dir / "p.exr";
    ASSERT_EQ(run(render + "--out " + picture.string() + " --aov " + aov.string()).status, 0);
    const std::uint64_t pictureSize = std::filesystem::file_size(picture),
                        aovSize = std::filesystem::file_size(aov);
    ASSERT_LT(pictureSize, aovSize);
    const std::uint64_t between = (pictureSize + aovSize) / 2;
    test::writeBytes(picture, kOld);
    expectFailsWhole("microrelief-render",
                     render + "--out " + picture.string() + " --aov " + aov.string(), aov, between);
    EXPECT_EQ(test::readBytes(picture), kOld);
}

TEST_F(FullDisk, MakeMapFailsWholeInEveryFormat) {
    const std::string makeMap = std::string(MICRORELIEF_MAKE_MAP_EXE) + " cobbles --size 64x64 ";
    for (const char* extension : {"png", "exr", "tif"}) {
        SCOPED_TRACE(extension);
        const auto whole = dir / (std::string("whole.") + extension),
                   file = dir / (std::string("map.") + extension);
        expectLargerThanTheLimit(makeMap + "--out " + whole.string(), whole);
        expectFailsWhole("microrelief-make-map", makeMap + "--out " + file.string(), file);
    }
    // The map and its albedo are one batch: the albedo failing leaves the old map too.
    const auto map = dir / "map.png", albedo = dir / "albedo.png";
    test::writeBytes(map, kOld);
    expectFailsWhole("microrelief-make-map",
                     makeMap + "--out " + map.string() + " --albedo " + albedo.string(), albedo);
    EXPECT_EQ(test::readBytes(map), kOld);
}

TEST_F(FullDisk, GlslBundleFailsWholeAndLeavesTheUsersTmp) {
    const std::string bundle =
        std::string(MICRORELIEF_GLSL_BUNDLE_EXE) + " " + MICRORELIEF_SHADER_SOURCE_DIR +
        "/microrelief/multilevel_trace.glsl" + " --root " + MICRORELIEF_SHADER_SOURCE_DIR + " ";
    const auto whole = dir / "whole.glsl", file = dir / "single.glsl";
    expectLargerThanTheLimit(bundle + "--out " + whole.string(), whole);
    // A user's file of the name the bundler once wrote through.
    const std::vector<std::uint8_t> users = {'m', 'i', 'n', 'e'};
    test::writeBytes(dir / "single.glsl.tmp", users);
    expectFailsWhole("microrelief-glsl-bundle", bundle + "--out " + file.string(), file);
    EXPECT_EQ(test::readBytes(dir / "single.glsl.tmp"), users);
    ASSERT_EQ(run(bundle + "--out " + file.string()).status, 0);
    EXPECT_EQ(test::readBytes(file), test::readBytes(whole));
    EXPECT_EQ(test::readBytes(dir / "single.glsl.tmp"), users);

    // Standard output redirected to a file on the full disk.
    const test::RunResult r = runLimited(bundle + "> " + (dir / "piped.glsl").string());
    test::expectOneLineFailure(r, "microrelief-glsl-bundle", 1,
                               "standard output: cannot write (File too large)");

    // A folder at --out: refused, the folder and the user's "<folder>.tmp" as they were.
    std::filesystem::create_directory(dir / "outdir");
    test::writeBytes(dir / "outdir.tmp", users);
    const test::RunResult folder = run(bundle + "--out " + (dir / "outdir").string());
    test::expectOneLineFailure(folder, "microrelief-glsl-bundle", 2, "outdir: is a directory");
    EXPECT_TRUE(std::filesystem::is_directory(dir / "outdir"));
    EXPECT_EQ(test::readBytes(dir / "outdir.tmp"), users);
}

// The benchmark's reports: rebuild.csv is written first, as the run goes.
TEST_F(FullDisk, BenchFailsWhole) {
    const std::string bench = std::string(MICRORELIEF_BENCH_EXE) +
                              " --rebuild --rebuild-sizes 33 --size 48x40 --out-dir ";
    expectLargerThanTheLimit(bench + (dir / "whole").string(), dir / "whole" / "rebuild.csv", 100);
    std::filesystem::create_directory(dir / "r");
    expectFailsWhole("microrelief-bench", bench + (dir / "r").string(), dir / "r" / "rebuild.csv",
                     100);
}

// A folder or FIFO at a target is refused with one line before any rendering (these run
// where no GL backend is, which would be the error if rendering started), and stays.
TEST_F(FullDisk, RenderRefusesAFolderOrFifoAtATargetBeforeRendering) {
    std::filesystem::create_directory(dir / "d.png");
    std::filesystem::create_directory(dir / "d.exr");
    std::filesystem::create_directory(dir / "v2.png");
    ASSERT_EQ(::mkfifo((dir / "f.png").c_str(), 0600), 0);
    const std::string out = " --out " + (dir / "x.png").string();
    struct Case {
        std::string args, mentions;
    };
    const std::vector<Case> cases = {
        {"--out " + (dir / "d.png").string(), "d.png: is a directory"},
        {out + " --aov " + (dir / "d.exr").string(), "d.exr: is a directory"},
        {"--out " + (dir / "f.png").string(), "f.png: is not a regular file"},
        // A later frame's file: refused before the first frame is drawn.
        {"--turntable 3 --out '" + (dir / "v{frame}.png").string() + "'", "v2.png: is a directory"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.args);
        const test::RunResult r = run(kNoGl + render + c.args);
        test::expectOneLineFailure(r, "microrelief-render", 2, c.mentions);
    }
    EXPECT_TRUE(std::filesystem::is_directory(dir / "d.png"));
    EXPECT_TRUE(std::filesystem::is_directory(dir / "d.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "v0.png"));
    EXPECT_EQ(test::hiddenFilesIn(dir.path()), std::vector<std::string>{});
}

}  // namespace
