// The C++ twin and its neighbours point at the GLSL they mirror in comments of the form
// "file.glsl: mr_name" (or "file.glsl's mr_name", "file.glsl, mr_name"). Such a pointer is
// only worth having while it is right: every one in the sources, the headers, the programs
// and the tests must name a file under shaders/ that defines what the pointer names (a
// function, a struct, a constant or a macro). A function renamed or moved to another file
// turns this red until the comment follows it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <vector>
#include <algorithm>
#include <sstream>

namespace {

const std::filesystem::path kShaders = MICRORELIEF_SHADER_SOURCE_DIR;
const std::filesystem::path kProject = kShaders.parent_path();

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Every shader file by its name (names are unique across shaders/).
std::map<std::string, std::filesystem::path> shaderFiles() {
    std::map<std::string, std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(kShaders)) {
        if (entry.is_regular_file()) files[entry.path().filename().string()] = entry.path();
    }
    return files;
}

// Whether `text` defines `name`: a function (a type, then the name and its parameters at
// the start of a line), a struct, a constant or a macro.
bool defines(const std::string& text, const std::string& name) {
    const std::regex definition(
        "^[ \\t]*(?:(?:const|highp|lowp|mediump|uniform|in|out|flat|layout[ \\t]*\\([^)]*\\))[ "
        "\\t]+)*[A-Za-z_][A-Za-z0-9_]*[ \\t]+" +
            name + "[ \\t]*(?:\\(|=|;)|^[ \\t]*struct[ \\t]+" + name +
            "\\b|^[ \\t]*#[ \\t]*define[ \\t]+" + name + "\\b",
        std::regex::ECMAScript | std::regex::multiline);
    return std::regex_search(text, definition);
}

}  // namespace

TEST(ShaderPointers, EveryPointerFromCppToGlslResolves) {
    const auto shaders = shaderFiles();
    // A shader file's name, then an identifier that is a name of code: the library's
    // prefixes, or a camelCase word (a pointer to a function without the prefix is stale).
    const std::regex pointer(
        R"(\b([a-z_0-9]+\.(?:glsl|frag|vert))(?::|'s|,)\s+((?:mr_|MR_|MICRORELIEF_)[A-Za-z0-9_]+|[a-z]+[A-Z][A-Za-z0-9]*))");
    int checked = 0;
    for (const char* folder : {"src", "include", "app", "tests", "examples"}) {
        for (const auto& entry : std::filesystem::recursive_directory_iterator(kProject / folder)) {
            const std::string extension = entry.path().extension().string();
            if (!entry.is_regular_file() || (extension != ".cpp" && extension != ".h")) continue;
            if (entry.path().filename() == "ShaderPointerTest.cpp") continue;  // its examples
            std::istringstream lines(readText(entry.path()));
            std::string line;
            for (int number = 1; std::getline(lines, line); ++number) {
                for (std::sregex_iterator m(line.begin(), line.end(), pointer), end; m != end;
                     ++m) {
                    const std::string file = (*m)[1], name = (*m)[2];
                    const std::string where =
                        std::filesystem::relative(entry.path(), kProject).string() + ":" +
                        std::to_string(number) + ": " + file + ": " + name;
                    ++checked;
                    const auto shader = shaders.find(file);
                    if (shader == shaders.end()) {
                        ADD_FAILURE() << where << ": no such file under shaders/";
                        continue;
                    }
                    EXPECT_TRUE(defines(readText(shader->second), name))
                        << where << ": " << file << " does not define " << name;
                }
            }
        }
    }
    EXPECT_GT(checked, 10);  // the pattern still finds the pointers
}

// The other direction, and every other pointer to a source file: a path to a .h, .cpp,
// .glsl, .frag or .vert named in the shaders, the sources, the programs, the tests, the
// examples, the scripts and the docs ("src/core/trace/MultilevelTracer.cpp",
// "core/heightmap/MaxPyramid.h", "microrelief/gl/Gl.h", "shaders/relief.frag") must name a
// file that exists: from the project's root, include/microrelief/, src/ or shaders/, or
// beside the file that names it. Files moved between folders turn this red until every
// comment and page follows them. Paths of other libraries' headers (glad/gl.h,
// GLFW/glfw3.h, ...) start elsewhere and are not checked; the few files made at build
// time are listed.
TEST(ShaderPointers, EveryPathToASourceFileResolves) {
    const std::regex path(
        R"((?:^|[^A-Za-z0-9_./-])((?:src|include|microrelief|core|io|gl|headless|glfw|app|tests|examples|shaders|packages)/[A-Za-z0-9_./-]*[A-Za-z0-9_]\.(?:h|cpp|glsl|frag|vert))\b)");
    const std::set<std::string> generated = {"microrelief/Version.h", "core/GlslConstants.h",
                                             "microrelief/core/GlslConstants.h",
                                             "gl/ReliefParameters.h",
                                             "microrelief/gl/ReliefParameters.h",
                                             "include/microrelief/core/GlslConstants.h",
                                             "include/microrelief/gl/ReliefParameters.h"};
    const std::set<std::string> textExtensions = {".cpp", ".h", ".glsl", ".frag", ".vert",
                                                  ".md",  ".js", ".mjs", ".py", ".sh",
                                                  ".txt", ".cmake", ".in"};
    int checked = 0;
    std::vector<std::filesystem::path> files;
    for (const char* folder :
         {"src", "include", "app", "tests", "examples", "shaders", "docs", "scripts", "cmake",
          "web", "packages/microrelief-three/src", "packages/microrelief-three/scripts",
          "packages/microrelief-three/glsl", "packages/microrelief-three/wasm"}) {
        for (const auto& entry : std::filesystem::recursive_directory_iterator(kProject / folder))
            if (entry.is_regular_file()) files.push_back(entry.path());
    }
    files.push_back(kProject / "README.md");
    files.push_back(kProject / "CMakeLists.txt");
    for (const auto& file : files) {
        const std::string extension = file.extension().string();
        if (!textExtensions.contains(extension) && file.filename() != "CMakeLists.txt") continue;
        if (file.filename() == "ShaderPointerTest.cpp") continue;  // its examples
        // A test's code names the scratch files it makes; its comments point at sources.
        const bool commentsOnly =
            std::filesystem::relative(file, kProject).begin()->string() == "tests";
        std::istringstream lines(readText(file));
        std::string line;
        for (int number = 1; std::getline(lines, line); ++number) {
            const std::size_t start = line.find_first_not_of(" \t");
            if (commentsOnly && (start == std::string::npos ||
                                 (line.compare(start, 2, "//") != 0 && line[start] != '#')))
                continue;
            for (std::sregex_iterator m(line.begin(), line.end(), path), end; m != end; ++m) {
                const std::string named = (*m)[1];
                if (generated.contains(named)) continue;
                ++checked;
                const bool found = std::ranges::any_of(
                    std::initializer_list<std::filesystem::path>{
                        kProject, kProject / "include" / "microrelief", kProject / "include",
                        kProject / "src", kShaders, file.parent_path()},
                    [&](const std::filesystem::path& root) {
                        return std::filesystem::exists(root / named);
                    });
                EXPECT_TRUE(found) << std::filesystem::relative(file, kProject).string() << ":"
                                   << number << ": " << named << ": no such file";
            }
        }
    }
    EXPECT_GT(checked, 100);  // the pattern still finds the paths
}
