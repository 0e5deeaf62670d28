// microrelief-viewer: the interactive viewer. Thin wiring: parse, open the window, run.
// On failure: one line on stderr and exit status 2 (bad arguments or input) or 1, as
// microrelief-render does.
#include "ViewerApp.h"

using namespace microrelief;

namespace {
constexpr const char* kProgram = "microrelief-viewer";
}  // namespace

int main(int argc, char** argv) {
    return runProgram<ViewerOptions>(kProgram, parseViewerOptions(argc, argv),
                                     [](const ViewerOptions& options) {
                                         ViewerApp viewer(options);
                                         return viewer.run();
                                     });
}
