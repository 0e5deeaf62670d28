// microrelief-viewer's command line where no window is needed: help, version, and the
// errors a user can make, which fail the way microrelief-render's do (exit status 2 and
// one line naming the flag or the file) before any window opens.
#include <gtest/gtest.h>

#include <cstdlib>

#include "TestSupport.h"
#include "microrelief/core/synth/SyntheticMaps.h"

using namespace microrelief;

namespace {

class ViewerCli : public ::testing::Test {
protected:
    // No display: nothing here may need one.
    // No display: nothing here may need one.
    test::RunResult run(const std::string& args) {
        return test::runCommand(
            std::string("DISPLAY= WAYLAND_DISPLAY= ") + MICRORELIEF_VIEWER_EXE + " " + args,
            dir.path());
    }

    static void expectFailure(const test::RunResult& r, int status, const std::string& mentions) {
        test::expectOneLineFailure(r, "microrelief-viewer", status, mentions);
    }

    test::ScratchDir dir;
};

TEST_F(ViewerCli, HelpListsTheRenderersSceneFlags) {
    const test::RunResult help = run("--help");
    EXPECT_EQ(help.status, 0);
    for (const char* flag :
         {"--height", "--channel", "--normalize", "--height-scale", "--eye", "--target", "--up",
          "--fovy", "--size", "--light", "--method", "--view", "--frames", "--screenshot"}) {
        EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
    }
    // The mesh base is named as microrelief-render's, which the viewer refuses (its help
    // offered it as any other base before).
    EXPECT_NE(help.out.find("mesh (the triangle mesh of --mesh; microrelief-render only so far)"),
              std::string::npos)
        << help.out;
    const test::RunResult version = run("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_NE(version.out.find("microrelief-viewer"), std::string::npos);
}

// No file the viewer writes is one it reads (issue 47): the map and its albedo stay as
// they were, through a link too; refused before any window.
TEST_F(ViewerCli, OutputsThatAreInputsAreRefused) {
    const auto map = dir / "c.png";
    test::writeMap(map, synth::valueNoise(16, 16, 4, 2, 3), PixelType::UInt16);
    std::filesystem::create_symlink(map, dir / "link.png");
    const std::vector<std::uint8_t> bytes = test::readBytes(map);
    for (const std::string flag : {"--save-map", "--screenshot", "--window-screenshot"}) {
        for (const auto& out : {map, dir / "link.png"}) {
            expectFailure(
                run("--height " + map.string() + " " + flag + " " + out.string()), 2,
                flag + " " + out.string() + ": the same file as --height " + map.string());
        }
    }
    expectFailure(run("--albedo " + map.string() + " --screenshot " + map.string()), 2,
                  "the same file as --albedo");
    EXPECT_EQ(test::readBytes(map), bytes);
}

TEST_F(ViewerCli, BadArgumentsExitTwo) {
    expectFailure(run("--size 0x10"), 2, "--size");
    expectFailure(run("--eye 1,2"), 2, "--eye");
    expectFailure(run("--fovy 180"), 2, "--fovy");
    expectFailure(run("--view sideways"), 2, "sideways");
    expectFailure(run("--method raymarch"), 2, "raymarch");
    // A readable range, not the largest double in 309 digits.
    const test::RunResult frames = run("--frames -1");
    expectFailure(frames, 2, "--frames must be 0 (run until the window closes) or more, got -1");
    EXPECT_LT(frames.err.size(), 120u) << frames.err;
    expectFailure(run("--no-such-flag"), 2, "--no-such-flag");
    expectFailure(run("--screenshot " + (dir / "x.unknownext").string()), 2, "x.unknownext");
    expectFailure(run("--background 1,1"), 2, "three numbers r,g,b");
    // The shader folder checked before any window: named as the flag, with what it lacks.
    expectFailure(run("--shader-dir " + (dir / "none").string()), 2, "none: no such folder");
    expectFailure(run("--shader-dir " + dir.path().string()), 2, "no relief.frag");
}

// The sculpting flags (issue 16): a bad brush, stroke, undo count or map file is a bad
// argument, refused before any window opens.
TEST_F(ViewerCli, BadSculptingFlagsExitTwo) {
    expectFailure(run("--stroke dig,0,0,1,1"), 2, "unknown brush 'dig'");
    expectFailure(run("--stroke raise,0,0,1"), 2, "got 'raise,0,0,1'");  // the whole value
    expectFailure(run("--stroke raise"), 2, "got 'raise'");
    expectFailure(run("--stroke raise,0,0,1,1.5"), 2, "0 to 1");
    expectFailure(run("--stroke raise,0,0,1,nan"), 2, "--stroke");
    expectFailure(run("--brush-radius 0"), 2, "--brush-radius");
    expectFailure(run("--brush-strength -1"), 2, "--brush-strength");
    expectFailure(run("--brush-strength inf"), 2, "--brush-strength");
    expectFailure(run("--undo -1"), 2, "--undo");
    // A GeoTIFF keeps a DEM's ground: not for the bundled map, an image.
    expectFailure(run("--save-map " + (dir / "m.tif").string()), 2,
                  "m.tif: a map is saved as a GeoTIFF only where it came from an elevation model");
    expectFailure(run("--save-map " + (dir / "m.jpg").string()), 2, "m.jpg: a map is saved as");
    expectFailure(run("--animate tides"), 2, "--animate 'tides'");
    // The brush paints one map: not a tiled one, nor an animated field.
    expectFailure(run("--tile 2,2 --stroke raise,0.2,0.5,0.8,0.5"), 2, "untiled map only");
    expectFailure(run("--tile 2,1 --sculpt"), 2, "untiled map only");
    expectFailure(run("--animate waves --stroke raise,0.2,0.5,0.8,0.5"), 2, "animated relief");
    expectFailure(run("--animate flood --undo 1"), 2, "animated relief");
    expectFailure(run("--undo 3"), 2, "--undo 3: more than the 0 --stroke given");
    expectFailure(run("--stroke raise,0,0,1,1 --undo 2"), 2, "more than the 1 --stroke");
}

// Outputs that cannot be written as asked (issue 25), refused as microrelief-render refuses
// them and before any window (there is no display here, which would be the error
// otherwise): a folder at the path (it was moved away and "saved"), one file for two
// outputs (the map replaced the screenshot).
TEST_F(ViewerCli, OutputsThatCannotBeWrittenExitTwoBeforeAnyWindow) {
    const std::string folder = (dir / "d.png").string(), same = (dir / "same.png").string();
    std::filesystem::create_directory(folder);
    for (const char* flag : {"--save-map ", "--screenshot ", "--window-screenshot "}) {
        expectFailure(run(flag + folder), 2, folder + ": is a directory");
        // A folder without an extension is named as a folder too, not as a name without one.
        expectFailure(run(flag + dir.path().string()), 2, dir.path().string() + ": is a directory");
    }
    expectFailure(run("--save-map " + same + " --screenshot " + same), 2, "given for two outputs");
    expectFailure(run("--screenshot " + same + " --window-screenshot " + same), 2,
                  "given for two outputs");
    EXPECT_TRUE(std::filesystem::is_directory(folder));
    EXPECT_FALSE(std::filesystem::exists(same));
    EXPECT_EQ(test::hiddenFilesIn(dir.path()), std::vector<std::string>{});
}

TEST_F(ViewerCli, BadMapsAndCamerasExitTwoBeforeAnyWindow) {
    expectFailure(run("--height " + (dir / "missing.png").string()), 2, "missing.png");
    // OpenImageIO's probes used to read /dev/zero forever (issue 15).
    expectFailure(run("--height /dev/zero"), 2, "/dev/zero: is not a regular file");
    expectFailure(run("--eye 0,1,0 --target 0,0,0 --up 0,1,0"), 2, "--up");
}

TEST_F(ViewerCli, NoDisplayExitsOneWithOneLine) {
    const test::RunResult r = run("--frames 1");
    expectFailure(r, 1, "GLFW");
}

}  // namespace
