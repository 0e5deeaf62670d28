// microrelief-viewer: the interactive viewer. Thin wiring: parse, open the window, run.
// On failure: one line on stderr and exit status 2 (bad arguments or input) or 1, as
// microrelief-render does.
#include <iostream>

#include "ViewerApp.h"
#include "core/Error.h"
#include "core/Log.h"

using namespace microrelief;

namespace {

constexpr const char* kProgram = "microrelief-viewer";

int fail(int status, const std::string& message) {
    std::cerr << kProgram << ": error: " << message << '\n';
    return status;
}

}  // namespace

int main(int argc, char** argv) {
    ViewerParseResult parsed = parseViewerOptions(argc, argv);
    if (!parsed.options) {
        if (parsed.exitStatus != 0) return fail(parsed.exitStatus, parsed.message);
        std::cout << parsed.message << '\n';
        return 0;
    }
    const bool verbose = parsed.options->verbose;
    setLogSink([verbose](LogLevel level, const std::string& message) {
        if (level == LogLevel::Info && !verbose) return;
        std::cerr << kProgram << ": " << (level == LogLevel::Warning ? "warning: " : "") << message
                  << '\n';
    });
    try {
        ViewerApp viewer(*parsed.options);
        return viewer.run();
    } catch (const Error& e) {
        return fail(e.exitStatus(), e.what());
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
}
