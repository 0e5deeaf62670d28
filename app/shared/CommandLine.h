// What every program's command line and main() share (microrelief-render,
// microrelief-viewer): parsing with CLI11 into an options struct, --help and --version,
// and the spec's failure shape: exactly one line "<program>: error: ..." on stderr, exit
// status 2 for bad arguments or input and 1 for anything else.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <iostream>
#include <new>
#include <optional>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"

namespace microrelief {

template <class Options>
struct ParseResult {
    std::optional<Options> options;  // empty: nothing to run
    int exitStatus = 0;              // when empty: 0 after --help/--version, 2 on error
    std::string message;             // the help text, the version, or the error
};

// Parses argv with `app`, whose options write into the caller's variables, then calls
// `finish` to turn them into Options (it throws Error(BadInput) for a bad value).
template <class Options>
ParseResult<Options> parseCommandLine(CLI::App& app, int argc, char** argv,
                                      const std::function<Options()>& finish) {
    ParseResult<Options> result;
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        result.message = app.help();
        return result;
    } catch (const CLI::CallForVersion& e) {
        result.message = e.what();
        return result;
    } catch (const CLI::ParseError& e) {
        result.exitStatus = 2;
        result.message = std::string(e.what()) + " (see --help)";
        return result;
    }
    try {
        result.options = finish();
    } catch (const Error& e) {
        result.exitStatus = 2;
        result.message = e.what();
    }
    return result;
}

// main() for a program: prints the help or the error of `parsed`, installs a log sink
// (information only with the options' `verbose`), runs `body` and turns its Error into
// one line and the exit status the error's kind calls for.
template <class Options>
int runProgram(const char* program, ParseResult<Options>&& parsed,
               const std::function<int(const Options&)>& body) {
    auto fail = [program](int status, const std::string& message) {
        std::cerr << program << ": error: " << message << '\n';
        return status;
    };
    if (!parsed.options) {
        if (parsed.exitStatus != 0) return fail(parsed.exitStatus, parsed.message);
        std::cout << parsed.message << '\n';
        return 0;
    }
    const bool verbose = parsed.options->verbose;
    setLogSink([program, verbose](LogLevel level, const std::string& message) {
        if (level == LogLevel::Info && !verbose) return;
        std::cerr << program << ": " << (level == LogLevel::Warning ? "warning: " : "") << message
                  << '\n';
    });
    try {
        return body(*parsed.options);
    } catch (const Error& e) {
        return fail(e.exitStatus(), e.what());
    } catch (const std::bad_alloc&) {
        // Where a file is at stake the library names it (an Error); this is the rest.
        return fail(1, "out of memory");
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
}

}  // namespace microrelief
