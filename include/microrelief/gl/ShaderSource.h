// GLSL sources assembled on the host (Magnum GL/Shader.cpp style): the host prepends
// `#version` and feature `#define`s, splices relative `#include "..."` files in place,
// and marks every splice with `#line <line> <file index>` so that a compiler message
// can be mapped back to the real file and line with mapCompilerLog().
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace microrelief {

struct ShaderSource {
    std::string text;                          // ready for glShaderSource
    std::vector<std::filesystem::path> files;  // source-string number -> file
    std::string version;                       // e.g. "330 core", "300 es"
};

// The largest file an #include splices (and the file assembly starts from): a GLSL
// source is tens of kilobytes; a larger file is no shader (a device, a data file).
inline constexpr long long kMaxShaderFileBytes = 4LL << 20;

struct ShaderDefine {
    std::string name;
    std::string value;  // may be empty: `#define NAME`
};

// Reads `file`, resolving each `#include "relative/path"` against the including file's
// folder, then against each of `includeDirs` in order (an engine's shader in its own
// folder includes "microrelief/multilevel_trace.glsl" with the library's shader folder,
// microrelief_SHADER_DIR, here). Each file is spliced once, however often it is included
// (the library's include guards would make repeats empty anyway).
// What is spliced (docs/reliability-inputs.md): only regular files of at most
// kMaxShaderFileBytes whose real path (links resolved) lies inside `file`'s folder or one
// of `includeDirs`; a name is relative, never absolute, and may not lead out of them
// with "..". Only `#include "name"` alone on its line is an include; `#include <name>`,
// an unclosed quote or text after the name is an error. A FIFO, device or folder is
// refused before it is read. Throws Error(Runtime: the program's own shaders are at
// fault, not the user) in one line,
// "<including file>:<line>: #include ...: <reason>", for each of these, a missing
// include or nesting deeper than 32 (a cycle).
ShaderSource assembleShader(const std::filesystem::path& file, const std::string& version,
                            const std::vector<ShaderDefine>& defines = {},
                            const std::vector<std::filesystem::path>& includeDirs = {});

// `file` with its includes spliced in the same way, as one text an engine without an
// include resolver can paste after its own `#version` and option `#define`s: no #version,
// no #line, each spliced file between "// ---- begin <path> ----" and "// ---- end ..."
// comments, its path relative to `root` (default: the file's folder). The includes are
// taken as assembleShader takes them, with `root` (which must hold `file`) in place of
// the file's folder, and Error(BadInput) for what assembleShader refuses (the user's
// files are at fault). The library's single-file tracers (share/microrelief/shaders/single/)
// are made so at build time.
std::string bundleShader(const std::filesystem::path& file, const std::filesystem::path& root = {},
                         const std::vector<std::filesystem::path>& includeDirs = {});

// Rewrites the "<index>:<line>(<col>)" (Mesa) and "<index>(<line>)" (NVIDIA, glslang
// "ERROR: <index>:<line>:") prefixes of a compiler log into "<file>:<line>".
std::string mapCompilerLog(const std::string& log, const std::vector<std::filesystem::path>& files);

}  // namespace microrelief
