// microrelief-glsl-bundle: a GLSL file with its #include "..." files spliced in, as one
// file for engines that have no include resolver (gl/ShaderSource.h: bundleShader). The
// build makes the library's single-file tracers with it (share/microrelief/shaders/single).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "CommandLine.h"
#include "microrelief/Version.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/gl/ShaderSource.h"
#include "microrelief/io/AtomicFile.h"

namespace {

// Whether some of the paths are absolute and some relative (an empty root is none).
bool mixedPaths(const std::filesystem::path& input, const std::filesystem::path& root,
                const std::vector<std::filesystem::path>& includeDirs) {
    std::vector<std::filesystem::path> paths{input};
    if (!root.empty()) paths.push_back(root);
    paths.insert(paths.end(), includeDirs.begin(), includeDirs.end());
    return std::any_of(paths.begin(), paths.end(),
                       [&](const auto& p) { return p.is_absolute() != input.is_absolute(); });
}

// The files the bundle spliced in, as its "// ---- begin <path> ----" markers name them
// (from the root), the bundled file's own first.
std::vector<std::filesystem::path> splicedFiles(const std::string& bundled) {
    const std::string begin = "// ---- begin ", end = " ----";
    std::vector<std::filesystem::path> files;
    std::istringstream lines(bundled);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.size() > begin.size() + end.size() && line.rfind(begin, 0) == 0 &&
            line.compare(line.size() - end.size(), end.size(), end) == 0)
            files.emplace_back(line.substr(begin.size(), line.size() - begin.size() - end.size()));
    }
    return files;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Splices a GLSL file's #include \"...\" files into one file (each once, marked by "
        "comments; no #version, no #line): the microrelief GLSL library for engines without an "
        "include resolver."};
    std::filesystem::path input, root, output;
    std::vector<std::filesystem::path> includeDirs;
    app.add_option("file", input, "The GLSL file to bundle")->required();
    app.add_option("--root", root,
                   "Name spliced files relative to this folder (default: the file's)");
    app.add_option("-I,--include-dir", includeDirs,
                   "A folder to search for #include \"name\" after the including file's own "
                   "folder; repeatable, searched in the order given (e.g. -I share/microrelief/"
                   "shaders for \"microrelief/shadow.glsl\")");
    app.add_option("--out", output, "Output file (default: standard output)");
    app.set_version_flag("--version",
                         std::string("microrelief-glsl-bundle ") + MICRORELIEF_VERSION_STRING);
    if (const auto status =
            microrelief::parseArgumentsOrExit(app, argc, argv, "microrelief-glsl-bundle"))
        return *status;
    try {
        std::error_code ec;
        if (!std::filesystem::exists(input, ec) && !ec)
            microrelief::throwBadInput(input.string() + ": no such file");
        if (!std::filesystem::is_regular_file(input, ec))
            microrelief::throwBadInput(input.string() + ": not a regular file");
        for (const std::filesystem::path& folder : includeDirs)
            if (!std::filesystem::is_directory(folder, ec))
                microrelief::throwBadInput("-I " + microrelief::printable(folder.string()) +
                                           ": not a directory");
        if (!root.empty() && !std::filesystem::is_directory(root, ec)) {
            microrelief::throwBadInput(
                "--root " + microrelief::printable(root.string()) +
                (std::filesystem::exists(root, ec) ? ": not a directory" : ": no such directory"));
        }
        // The markers name each file by its path from the root, which needs the two alike:
        // where some are absolute and some relative, all are made absolute.
        if (mixedPaths(input, root, includeDirs)) {
            input = std::filesystem::absolute(input);
            if (!root.empty()) root = std::filesystem::absolute(root);
            for (std::filesystem::path& folder : includeDirs)
                folder = std::filesystem::absolute(folder);
        }
        const std::string header = "// " + input.filename().string() +
                                   " of the microrelief GLSL library, its includes spliced in by "
                                   "microrelief-glsl-bundle " MICRORELIEF_VERSION_STRING
                                   ". Prepend #version and any option #defines.\n";
        const std::string bundled = microrelief::bundleShader(input, root, includeDirs);
        const std::string text = header + bundled;
        if (!output.empty()) {
            // The output is none of the files read: the one bundled, nor any spliced in.
            std::vector<microrelief::NamedFile> read{{input, "the bundled"}};
            const std::filesystem::path base = root.empty() ? input.parent_path() : root;
            for (const std::filesystem::path& spliced : splicedFiles(bundled))
                read.push_back({base / spliced, "the included"});
            microrelief::checkOutputsAreNotInputs({{output, "--out"}}, read);
        }
        if (output.empty()) {
            // Checked as a file is: standard output may be one, on a full disk.
            if (!microrelief::writeAll(1, text.data(), text.size()))
                microrelief::throwRuntime(std::string("standard output: cannot write (") +
                                          std::strerror(errno) + ")");
        } else {
            // Whole or not at all, through a temporary of its own beside the target.
            microrelief::writeFileAtomically(output, text);
        }
    } catch (const microrelief::Error& e) {
        std::fprintf(stderr, "microrelief-glsl-bundle: error: %s\n",
                     microrelief::printable(e.what()).c_str());
        return exitStatusOf(e.kind());
    }
    return 0;
}
