// What a program reads is never what it writes (issue 47): microrelief-render's picture, AOV
// and manifest, microrelief-glsl-bundle's output and microrelief-bench's reports refused
// over a file the run reads, by name, through a symbolic link and through a hard link, with
// the input's bytes as they were. And the pyramid cache's names: a FIFO where a pyramid file
// goes is refused, not waited on; a folder name too long is said in one line.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "TestSupport.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

class InputSafetyCli : public ::testing::Test {
protected:
    // Run in the scratch folder, where the relative names given lie.
    test::RunResult render(const std::string& args, const std::string& prefix = "") {
        return test::runCommand("cd " + dir.path().string() + " && " + prefix + " " +
                                    MICRORELIEF_RENDER_EXE + small + args,
                                dir.path());
    }
    test::RunResult bundle(const std::string& args) {
        return test::runCommand(
            "cd " + dir.path().string() + " && " + MICRORELIEF_GLSL_BUNDLE_EXE + " " + args,
            dir.path());
    }
    // A file the run reads: its bytes must be the same after a refused run.
    struct Kept {
        std::filesystem::path file;
        std::vector<std::uint8_t> bytes;
    };
    Kept keep(const std::filesystem::path& file) { return {file, test::readBytes(file)}; }
    static void expectUnchanged(const Kept& kept) {
        EXPECT_EQ(test::readBytes(kept.file), kept.bytes) << kept.file << " was written";
    }

    test::ScratchDir dir;
    const std::string small = " --size 32x24 --backend auto ";
};

// Each case names an output that is an input (`same`, the input's flag and name in the
// message); the run exits 2 before anything is drawn, and the input is as it was.
TEST_F(InputSafetyCli, RenderNeverWritesOverAFileItReads) {
    const auto map = dir / "c.png", exr = dir / "m.exr", albedo = dir / "colours.png";
    test::writeMap(map, synth::valueNoise(16, 16, 4, 2, 3), PixelType::UInt16);
    test::writeMap(exr, synth::valueNoise(16, 16, 4, 2, 5), PixelType::Float);
    test::writeMap(albedo, synth::valueNoise(16, 16, 4, 2, 9), PixelType::UInt8);
    std::filesystem::create_symlink(map, dir / "link.png");
    std::filesystem::create_hard_link(map, dir / "hard.png");
    std::ofstream(dir / "cams.csv") << "eye_x,eye_y,eye_z,target_x,target_y,target_z\n"
                                       "0.9,0.6,0.5,0,0,0\n";
    const std::string m = map.string();
    struct Case {
        std::string args, message;
    };
    const std::vector<Case> cases{
        {"--height " + m + " --out " + m, "--out " + m + ": the same file as --height " + m},
        {"--height " + m + " --out " + (dir / "link.png").string(), "the same file as --height"},
        {"--height " + m + " --out " + (dir / "hard.png").string(), "the same file as --height"},
        {"--height " + (dir / "sub" / ".." / "c.png").string() + " --out " + m,
         "the same file as --height"},
        {"--height " + exr.string() + " --out x.png --aov " + exr.string(),
         "--aov " + exr.string() + ": the same file as --height"},
        {"--albedo " + albedo.string() + " --out " + albedo.string(), "the same file as --albedo"},
        // Camera paths: a frame, the manifest, over the map or the camera file.
        {"--height " + (dir / "c0.png").string() + " --turntable 2 --out '" +
             (dir / "c{frame}.png").string() + "'",
         "--out " + (dir / "c0.png").string() + ": the same file as --height"},
        {"--height " + m + " --turntable 2 --out 'v{frame}.png' --manifest " + m,
         "--manifest " + m + ": the same file as --height"},
        {"--cameras " + (dir / "cams.csv").string() + " --out 'v{frame}.png' --manifest " +
             (dir / "cams.csv").string(),
         "the same file as --cameras"},
    };
    std::filesystem::create_directory(dir / "sub");
    test::writeBytes(dir / "c0.png", test::readBytes(map));
    const Kept kept[] = {keep(map), keep(exr), keep(albedo), keep(dir / "cams.csv"),
                         keep(dir / "c0.png")};
    for (const Case& c : cases) {
        const test::RunResult r = render(c.args);
        test::expectOneLineFailure(r, "microrelief-render", 2, c.message);
        EXPECT_NE(r.err.find("which this run reads; writing it would replace it"),
                  std::string::npos)
            << r.err;
    }
    for (const Kept& k : kept) expectUnchanged(k);
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "v0.png"));
    // Outputs beside the inputs, none of them one, are drawn.
    const test::RunResult drawn = render(
        "--height " + m + " --albedo " + albedo.string() + " --turntable 2 --out '" +
        (dir / "d{frame}.png").string() + "' --aov '" + (dir / "d{frame}.exr").string() + "'");
    EXPECT_EQ(drawn.status, 0) << drawn.err;
}

TEST_F(InputSafetyCli, TheBundlerNeverWritesOverItsSourceOrItsIncludes) {
    std::filesystem::create_directories(dir / "lib");
    std::ofstream(dir / "m.glsl") << "#include \"lib/a.glsl\"\nvoid main() {}\n";
    std::ofstream(dir / "lib" / "a.glsl") << "float a() { return 1.0; }\n";
    std::filesystem::create_symlink(dir / "m.glsl", dir / "link.glsl");
    std::filesystem::create_hard_link(dir / "lib" / "a.glsl", dir / "hard.glsl");
    const Kept kept[] = {keep(dir / "m.glsl"), keep(dir / "lib" / "a.glsl")};
    const std::string source = (dir / "m.glsl").string();
    for (const auto& [out, message] : std::vector<std::pair<std::string, std::string>>{
             {source, "the same file as the bundled " + source},
             {(dir / "link.glsl").string(), "the same file as the bundled"},
             {(dir / "lib" / "a.glsl").string(), "the same file as the included"},
             {(dir / "hard.glsl").string(), "the same file as the included"},
             {(dir / "lib" / ".." / "m.glsl").string(), "the same file as the bundled"}}) {
        test::expectOneLineFailure(bundle(source + " --out " + out), "microrelief-glsl-bundle", 2,
                                   "--out " + out + ": " + message);
    }
    for (const Kept& k : kept) expectUnchanged(k);
    EXPECT_EQ(bundle(source + " --out " + (dir / "b.glsl").string()).status, 0);
}

// --root: a folder, and the markers name each file from it whether the paths are given
// absolute or relative (an absolute root with a relative file lost every name).
TEST_F(InputSafetyCli, TheBundlersRootIsAFolderAndItsMarkersNameTheFiles) {
    std::filesystem::create_directories(dir / "lib");
    std::ofstream(dir / "m.glsl") << "#include \"lib/a.glsl\"\nvoid main() {}\n";
    std::ofstream(dir / "lib" / "a.glsl") << "float a() { return 1.0; }\n";
    test::expectOneLineFailure(bundle("m.glsl --root m.glsl"), "microrelief-glsl-bundle", 2,
                               "--root m.glsl: not a directory");
    test::expectOneLineFailure(bundle("m.glsl --root nowhere"), "microrelief-glsl-bundle", 2,
                               "--root nowhere: no such directory");
    const std::string absolute = dir.path().string();
    for (const std::string& args : std::vector<std::string>{
             "m.glsl --root " + absolute, (dir / "m.glsl").string() + " --root .",
             "m.glsl --root .", (dir / "m.glsl").string() + " --root " + absolute}) {
        const test::RunResult r = bundle(args);
        ASSERT_EQ(r.status, 0) << args << ": " << r.err;
        for (const char* marker : {"// ---- begin m.glsl ----\n", "// ---- begin lib/a.glsl ----\n",
                                   "// ---- end lib/a.glsl ----\n", "// ---- end m.glsl ----\n"})
            EXPECT_NE(r.out.find(marker), std::string::npos) << args << ": " << marker << r.out;
    }
}

// A map measured is no file the bench writes into --out-dir: a plot over the map it plots.
TEST_F(InputSafetyCli, TheBenchNeverWritesOverAMapItMeasures) {
    const auto plot = dir / "out" / "time_vs_size.png";
    std::filesystem::create_directories(plot.parent_path());
    test::writeMap(plot, synth::valueNoise(16, 16, 4, 2, 3), PixelType::UInt16);
    const Kept kept = keep(plot);
    const test::RunResult r = test::runCommand(
        std::string(MICRORELIEF_BENCH_EXE) + " --maps " + plot.string() + " --out-dir " +
            (dir / "out").string() + " --map-sizes 0 --views 45 --frames 10 --methods multilevel",
        dir.path());
    test::expectOneLineFailure(
        r, "microrelief-bench", 2,
        "--out-dir " + plot.string() + ": the same file as the map " + plot.string());
    expectUnchanged(kept);
}

// Where the map's pyramid file goes there is a FIFO, or a link to one: refused in one
// line, never opened to wait for a writer (`timeout` turns a hang into a failure). A
// folder name longer than a file system takes is named in one line, exit 2.
TEST_F(InputSafetyCli, ThePyramidCacheRefusesFifosAndNamesTooLong) {
    const auto map = dir / "c.png", cache = dir / "cache";
    test::writeMap(map, synth::valueNoise(16, 16, 4, 2, 3), PixelType::UInt16);
    const std::string args = "--height " + map.string() + " --pyramid-cache " + cache.string();
    ASSERT_EQ(render(args + " -q --out " + (dir / "a.png").string()).status, 0);
    std::vector<std::filesystem::path> built;
    for (const auto& entry : std::filesystem::directory_iterator(cache))
        built.push_back(entry.path());
    ASSERT_EQ(built.size(), 1u);
    const std::filesystem::path pyramid = built[0];
    std::filesystem::remove(pyramid);
    ASSERT_EQ(::mkfifo(pyramid.c_str(), 0600), 0);
    test::RunResult r = render(args + " --out " + (dir / "b.png").string(), "timeout 20");
    test::expectOneLineFailure(r, "microrelief-render", 2,
                               pyramid.string() + ": is not a regular file");
    std::filesystem::remove(pyramid);
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    std::filesystem::create_symlink(dir / "fifo", pyramid);
    r = render(args + " --out " + (dir / "b.png").string(), "timeout 20");
    test::expectOneLineFailure(r, "microrelief-render", 2,
                               pyramid.string() + ": is not a regular file");
    EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));

    // A map whose name is as long as a file's may be: its pyramid file's name is cut to fit.
    const auto longMap = dir / (std::string(240, 'm') + ".png");
    std::filesystem::copy_file(map, longMap);
    r = render("--height " + longMap.string() + " --pyramid-cache " + cache.string() +
               " -q --out " + (dir / "long.png").string());
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "long.png"));

    const std::string tooLong = (dir / std::string(300, 'a')).string();
    for (const std::string& folder : {tooLong, tooLong + "/cache"}) {
        r = render("--height " + map.string() + " --pyramid-cache " + folder + " --out " +
                   (dir / "b.png").string());
        test::expectOneLineFailure(
            r, "microrelief-render", 2,
            folder + ": cannot be the pyramid files' cache (File name too long)");
    }
}

// CLI11's own messages in the programs' words (parseErrorText, wholeNumberIn).
TEST_F(InputSafetyCli, FlagErrorsAreWordedAsTheProgramsOthers) {
    const auto expect = [&](const std::string& args, const std::string& message) {
        test::expectOneLineFailure(render(args), "microrelief-render", 2,
                                   message + " (see --help)");
    };
    expect("--height", "error: --height needs a value");
    expect("--out x.png --backend", "error: --backend needs a value");
    for (const char* memory : {"abc", "0", "1.5", "1e3", "1048577"})
        expect(std::string("--memory ") + memory, std::string("error: --memory: '") + memory +
                                                      "' is not a whole number from 1 to 1048576");
    test::expectOneLineFailure(
        test::runCommand(std::string(MICRORELIEF_BENCH_EXE) + " --memory x", dir.path()),
        "microrelief-bench", 2, "error: --memory: 'x' is not a whole number from 1 to 1048576");
    test::expectOneLineFailure(bundle("m.glsl -I"), "microrelief-glsl-bundle", 2,
                               "error: --include-dir needs a value");

    // The AOV's extension in any case, as --out's.
    const test::RunResult upper =
        render("--out " + (dir / "a.PNG").string() + " --aov " + (dir / "a.EXR").string());
    EXPECT_EQ(upper.status, 0) << upper.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "a.EXR"));
    test::expectOneLineFailure(render("--out x.png --aov " + (dir / "a.Png").string()),
                               "microrelief-render", 2, "the AOV must be an OpenEXR file");

    // A height scale too small for the shader: the advice is not a flag already given.
    const test::RunResult tiny = render("--normalize --height-scale 1e-40 --out x.png");
    test::expectOneLineFailure(tiny, "microrelief-render", 2, "raise --height-scale");
    EXPECT_EQ(tiny.err.find("use --normalize"), std::string::npos) << tiny.err;
}

}  // namespace
