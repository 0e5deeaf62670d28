// What every program's command line and main() share: parsing with CLI11 into an options
// struct (microrelief-render, microrelief-viewer: parseCommandLine, runProgram) or into a
// program's own variables (make-map, bench, glsl-bundle: parseArgumentsOrExit), --help and
// --version, and the spec's failure shape: exactly one line "<program>: error: ..." on
// stderr, exit status 2 for bad arguments or input and 1 for anything else.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <functional>
#include <iostream>
#include <new>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "SceneOptions.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"
#include "microrelief/core/Machine.h"  // availableMemoryBytes, which the programs' limits use
#include "microrelief/core/Text.h"

namespace microrelief {

// An option given an empty value (--cameras '', --height "") means nothing a program can
// do, and taking it as absent (the default map, no camera path) does something the user
// did not ask for: refused, with `where` in front. Flags take no value and pass.
inline void refuseEmptyValues(const CLI::App& app, const std::string& where = "") {
    for (const CLI::Option* option : app.get_options()) {
        if (option->count() == 0 || option->get_type_size_min() == 0) continue;
        for (const std::string& value : option->results()) {
            if (value.empty())
                throwBadInput(where + option->get_name() + " needs a value, got an empty one");
        }
    }
}

// The words CLI11 did not expect (`app.remaining()`, in the order given), in the programs'
// words: the options not known ("--heigth is not an option"; the words after them are
// likely their values), or else the words. (CLI11's own message, "The following arguments
// were not expected: maps/b.png --heigth", lists them last first, joined with spaces.)
inline std::string unexpectedArgumentsText(const std::vector<std::string>& words) {
    std::vector<std::string> options;
    // An option is "-x" or "--x..." with x a letter ("-1" is a stray number), named up to
    // any '=' ("--heigth=a.png").
    for (const std::string& word : words) {
        const std::size_t letter = word.rfind("--", 0) == 0 ? 2 : 1;
        if (word.size() > letter && word[0] == '-' &&
            std::isalpha(static_cast<unsigned char>(word[letter])))
            options.push_back(word.substr(0, word.find('=')));
    }
    const auto join = [](const std::vector<std::string>& parts) { return joinWords(parts, " and "); };
    if (options.empty()) {
        std::vector<std::string> quoted;
        for (const std::string& word : words) quoted.push_back("'" + word + "'");
        return join(quoted) + (words.size() > 1 ? " were" : " was") +
               " not expected (options are given as --name VALUE)";
    }
    return join(options) + (options.size() > 1 ? " are not options" : " is not an option");
}

// CLI11's parse error in the programs' words: an option given twice, an option without its
// value, a flag given one, a value that is not of the option's type and arguments not
// expected said plainly (CLI11 says "--size: At Most 1 required but received 2", "--height:
// 1 required TEXT missing", "--quiet: too many inputs for a flag", "Could not convert:
// --channel = 1.5" and "The following argument was not expected: --heigth"); the others as
// CLI11 puts them. `app` is the one that threw, which holds the words it did not expect.
inline std::string parseErrorText(const CLI::ParseError& e, const CLI::App& app) {
    std::string message = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e) && !app.remaining().empty())
        return unexpectedArgumentsText(app.remaining());
    // CLI11 2.1 to 2.4 write "At Most", later ones "At most": compared in lower case.
    std::string lower = message;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const std::string atMost = ": at most 1 required but received ";
    const std::string convert = "Could not convert: ";
    // "--height: 1 required TEXT missing": the option came last, without its value.
    static const std::regex missing(R"(^(\S+): \d+ required \S+ missing$)");
    // "--quiet: too many inputs for a flag", "-q was given a disallowed flag override".
    static const std::regex flagValue(
        R"(^(\S+)(: too many inputs for a flag| was given a disallowed flag override)$)");
    std::smatch match;
    if (const std::size_t at = lower.find(atMost); at != std::string::npos) {
        message = message.substr(0, at) + " is given more than once";
    } else if (std::regex_match(message, match, missing)) {
        message = match[1].str() + " needs a value";
    } else if (std::regex_match(message, match, flagValue)) {
        message = match[1].str() + " takes no value";
    } else if (message.rfind(convert, 0) == 0) {
        const std::size_t equals = message.find(" = ", convert.size());
        if (equals != std::string::npos) {
            message = message.substr(convert.size(), equals - convert.size()) + ": '" +
                      message.substr(equals + 3) + "' is not a value it takes";
        }
    }
    return message;
}

// A CLI11 check: a whole number from `lo` to `hi`, digits only, which fails as the
// programs' other flags do, "--memory: 'abc' is not a whole number from 1 to 1048576"
// (CLI11's Range says "Value abc not in range 1 to 1048576", and takes "1e3").
inline CLI::Validator wholeNumberIn(std::size_t lo, std::size_t hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            const bool digits = !text.empty() && text.size() <= 19 &&
                                text.find_first_not_of("0123456789") == std::string::npos;
            const unsigned long long value = digits ? std::stoull(text) : 0;
            if (digits && value >= lo && value <= hi) return {};
            return "'" + text + "' is not a whole number from " + std::to_string(lo) + " to " +
                   std::to_string(hi);
        },
        "UINT in [" + std::to_string(lo) + " - " + std::to_string(hi) + "]");
}

// A program's one line for a parse error: parseErrorText and where to look.
inline std::string parseErrorMessage(const CLI::ParseError& e, const CLI::App& app) {
    return parseErrorText(e, app) + " (see --help)";
}

// Parses argv for a program that keeps its options in its own variables (make-map, bench,
// glsl-bundle): after --help or --version, or on a parse error (one line, escaped like
// runProgram's), returns the status main() should exit with; empty when the program runs.
inline std::optional<int> parseArgumentsOrExit(CLI::App& app, int argc, char** argv,
                                               const char* program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
        std::cerr << program << ": error: " << printable(parseErrorMessage(e, app)) << '\n';
        return 2;
    }
    return std::nullopt;
}

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
        result.message = parseErrorMessage(e, app);
        return result;
    }
    try {
        refuseEmptyValues(app);
        result.options = finish();
    } catch (const Error& e) {
        result.exitStatus = 2;
        result.message = e.message(flagName);
    }
    return result;
}

// main() for a program: prints the help or the error of `parsed`, installs a log sink
// (information only with the options' `verbose`), runs `body` and turns its Error into
// one line and the exit status the error's kind calls for.
template <class Options>
int runProgram(const char* program, ParseResult<Options>&& parsed,
               const std::function<int(const Options&)>& body) {
    // Messages quote what users gave (file names, fields of a camera file): escaped, so
    // that a CR, a NUL or bytes that are no UTF-8 cannot garble or split the one line.
    auto fail = [program](int status, const std::string& message) {
        std::cerr << program << ": error: " << printable(message) << '\n';
        return status;
    };
    if (!parsed.options) {
        if (parsed.exitStatus != 0) return fail(parsed.exitStatus, parsed.message);
        std::cout << parsed.message << '\n';
        return 0;
    }
    const bool verbose = parsed.options->verbose;
    // A log message of several lines (a shader compiler's) keeps them, each escaped.
    setLogSink([program, verbose](LogLevel level, const std::string& message) {
        if (level == LogLevel::Info && !verbose) return;
        std::size_t start = 0;
        do {
            const std::size_t end = std::min(message.find('\n', start), message.size());
            std::cerr << program << ": " << (level == LogLevel::Warning ? "warning: " : "")
                      << printable(std::string_view(message).substr(start, end - start)) << '\n';
            start = end + 1;
        } while (start < message.size());
    });
    try {
        return body(*parsed.options);
    } catch (const Error& e) {
        return fail(exitStatusOf(e.kind()), e.message(flagName));
    } catch (const std::bad_alloc&) {
        // Where a file is at stake the library names it (an Error); this is the rest.
        return fail(1, "out of memory");
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
}

}  // namespace microrelief
