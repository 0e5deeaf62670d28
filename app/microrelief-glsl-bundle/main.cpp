// microrelief-glsl-bundle: a GLSL file with its #include "..." files spliced in, as one
// file for engines that have no include resolver (gl/ShaderSource.h: bundleShader). The
// build makes the library's single-file tracers with it (share/microrelief/shaders/single).
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "CommandLine.h"
#include "microrelief/Version.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/gl/ShaderSource.h"
#include "microrelief/io/AtomicFile.h"

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
        const std::string header = "// " + input.filename().string() +
                                   " of the microrelief GLSL library, its includes spliced in by "
                                   "microrelief-glsl-bundle " MICRORELIEF_VERSION_STRING
                                   ". Prepend #version and any option #defines.\n";
        const std::string text = header + microrelief::bundleShader(input, root, includeDirs);
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
        std::fprintf(stderr, "microrelief-glsl-bundle: error: %s\n", e.what());
        return exitStatusOf(e.kind());
    }
    return 0;
}
