// microrelief-viewer's command line where no window is needed: help, version, and the
// errors a user can make, which fail the way microrelief-render's do (exit status 2 and
// one line naming the flag or the file) before any window opens.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "TestSupport.h"

using namespace microrelief;

namespace {

struct RunResult {
    int status = -1;
    std::string out, err;
};

std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

class ViewerCli : public ::testing::Test {
protected:
    // No display: nothing here may need one.
    RunResult run(const std::string& args) {
        const std::string command = std::string("DISPLAY= WAYLAND_DISPLAY= ") +
                                    MICRORELIEF_VIEWER_EXE + " " + args + " > " +
                                    (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
        const int raw = std::system(command.c_str());
        return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(dir / "stdout"),
                slurp(dir / "stderr")};
    }

    static void expectFailure(const RunResult& r, int status, const std::string& mentions) {
        EXPECT_EQ(r.status, status) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind("microrelief-viewer: error: ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(mentions), std::string::npos)
            << "expected '" << mentions << "' in: " << r.err;
    }

    test::ScratchDir dir;
};

TEST_F(ViewerCli, HelpListsTheRenderersSceneFlags) {
    const RunResult help = run("--help");
    EXPECT_EQ(help.status, 0);
    for (const char* flag :
         {"--height", "--channel", "--normalize", "--height-scale", "--eye", "--target", "--up",
          "--fovy", "--size", "--light", "--method", "--view", "--frames", "--screenshot"}) {
        EXPECT_NE(help.out.find(flag), std::string::npos) << flag;
    }
    const RunResult version = run("--version");
    EXPECT_EQ(version.status, 0);
    EXPECT_NE(version.out.find("microrelief-viewer"), std::string::npos);
}

TEST_F(ViewerCli, BadArgumentsExitTwo) {
    expectFailure(run("--size 0x10"), 2, "--size");
    expectFailure(run("--eye 1,2"), 2, "--eye");
    expectFailure(run("--fovy 180"), 2, "--fovy");
    expectFailure(run("--view sideways"), 2, "sideways");
    expectFailure(run("--method raymarch"), 2, "raymarch");
    expectFailure(run("--frames -1"), 2, "--frames");
    expectFailure(run("--no-such-flag"), 2, "--no-such-flag");
    expectFailure(run("--screenshot " + (dir / "x.unknownext").string()), 2, "x.unknownext");
}

TEST_F(ViewerCli, BadMapsAndCamerasExitTwoBeforeAnyWindow) {
    expectFailure(run("--height " + (dir / "missing.png").string()), 2, "missing.png");
    expectFailure(run("--eye 0,1,0 --target 0,0,0 --up 0,1,0"), 2, "--up");
}

TEST_F(ViewerCli, NoDisplayExitsOneWithOneLine) {
    const RunResult r = run("--frames 1");
    expectFailure(r, 1, "GLFW");
}

}  // namespace
