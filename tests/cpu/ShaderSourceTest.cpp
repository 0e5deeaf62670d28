// Host-side GLSL assembly: #version and defines first, relative includes spliced with
// #line markers, and compiler messages mapped back to the real file and line.
#include <gtest/gtest.h>

#include <fstream>

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/gl/ShaderSource.h"

using namespace microrelief;

namespace {
void writeText(const std::filesystem::path& file, const std::string& text) {
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
}
}  // namespace

TEST(ShaderSource, VersionDefinesAndIncludesWithLineMarkers) {
    test::ScratchDir dir;
    writeText(dir / "lib/a.glsl",
              "#ifndef A_GLSL\n#define A_GLSL\nfloat a() { return 1.0; }\n#endif\n");
    writeText(dir / "main.frag",
              "// main\n#include \"lib/a.glsl\"\n#include \"lib/a.glsl\"\nvoid main() {}\n");
    const ShaderSource source =
        assembleShader(dir / "main.frag", "330 core", {{"FAST", ""}, {"N", "4"}});
    EXPECT_EQ(source.version, "330 core");
    ASSERT_EQ(source.files.size(), 2u);  // a.glsl once, however often it is included
    EXPECT_EQ(source.files[1].filename(), "a.glsl");
    // `#line index * 100000 + line index`: the file is in the line number as well, for
    // compilers that do not report the source string (Mesa).
    EXPECT_EQ(source.text,
              "#version 330 core\n#define FAST\n#define N 4\n"
              "#line 1 0\n// main\n"
              "#line 100001 1\n#ifndef A_GLSL\n#define A_GLSL\nfloat a() { return 1.0; }\n#endif\n"
              "#line 3 0\n"
              "#line 4 0\nvoid main() {}\n");
}

TEST(ShaderSource, NestedIncludesResolveAgainstTheIncludingFile) {
    test::ScratchDir dir;
    writeText(dir / "lib/inner/b.glsl", "float b() { return 2.0; }\n");
    writeText(dir / "lib/a.glsl", "#include \"inner/b.glsl\"\n");
    writeText(dir / "main.frag", "#include \"lib/a.glsl\"\n");
    const ShaderSource source = assembleShader(dir / "main.frag", "300 es");
    ASSERT_EQ(source.files.size(), 3u);
    EXPECT_NE(source.text.find("float b()"), std::string::npos);
}

// An engine's shader in its own folder reaches the library through a search folder; the
// including file's own folder still comes first.
TEST(ShaderSource, IncludesFallBackToTheSearchFoldersInOrder) {
    test::ScratchDir dir;
    writeText(dir / "library/microrelief/a.glsl", "float fromLibrary;\n");
    writeText(dir / "other/microrelief/a.glsl", "float fromOther;\n");
    writeText(dir / "engine/microrelief/local.glsl", "float local;\n");
    writeText(dir / "engine/main.frag",
              "#include \"microrelief/a.glsl\"\n#include \"microrelief/local.glsl\"\n");
    const ShaderSource source =
        assembleShader(dir / "engine/main.frag", "330 core", {}, {dir / "library", dir / "other"});
    EXPECT_NE(source.text.find("float fromLibrary;"), std::string::npos);
    EXPECT_EQ(source.text.find("float fromOther;"), std::string::npos);
    EXPECT_NE(source.text.find("float local;"), std::string::npos);
    EXPECT_THROW(assembleShader(dir / "engine/main.frag", "330 core"), Error);  // no search folder
    // The bundle for engines without a resolver: no #line, each file between comments.
    const std::string bundle =
        bundleShader(dir / "engine/main.frag", dir / "engine", {dir / "library"});
    EXPECT_EQ(bundle.find("#line"), std::string::npos);
    EXPECT_NE(bundle.find("// ---- begin main.frag ----"), std::string::npos);
    EXPECT_NE(bundle.find("float fromLibrary;"), std::string::npos);
}

TEST(ShaderSource, MissingIncludeNamesFileAndLine) {
    test::ScratchDir dir;
    writeText(dir / "main.frag", "\n\n#include \"nope.glsl\"\n");
    try {
        assembleShader(dir / "main.frag", "330 core");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("main.frag:3"), std::string::npos) << message;
        EXPECT_NE(message.find("nope.glsl"), std::string::npos) << message;
    }
}

TEST(ShaderSource, IncludeCycleEndsBecauseEachFileIsSplicedOnce) {
    test::ScratchDir dir;
    writeText(dir / "a.glsl", "#include \"b.glsl\"\nfloat a;\n");
    writeText(dir / "b.glsl", "#include \"a.glsl\"\nfloat b;\n");
    const ShaderSource source = assembleShader(dir / "a.glsl", "330 core");
    ASSERT_EQ(source.files.size(), 2u);
    EXPECT_NE(source.text.find("float b;\n"), std::string::npos);
    EXPECT_NE(source.text.find("float a;\n"), std::string::npos);
}

TEST(ShaderSource, CompilerLogsMapToFiles) {
    const std::vector<std::filesystem::path> files = {"shaders/relief.frag",
                                                      "shaders/microrelief/x.glsl"};
    // Mesa reports source string 0; the file is in the line number.
    EXPECT_EQ(mapCompilerLog("0:100012(5): error: `foo' undeclared", files),
              "shaders/microrelief/x.glsl:12:5: error: `foo' undeclared\n");
    // NVIDIA
    EXPECT_EQ(mapCompilerLog("0(7) : error C1008: undefined variable", files),
              "shaders/relief.frag:7 : error C1008: undefined variable\n");
    // glslang, which reports the source string too
    EXPECT_EQ(mapCompilerLog("ERROR: 1:100003: 'x' : undeclared identifier", files),
              "ERROR: shaders/microrelief/x.glsl:3: 'x' : undeclared identifier\n");
}

// The renderer's own assembly takes includes by the bundler's rules (issue 25): inside the
// start file's folder or a search folder, regular files only; the error names the
// including file and line, and is the environment's (Runtime: the program's shaders are
// broken), not the user's.
TEST(ShaderSource, IncludesOutsideTheFoldersOrNotRegularFilesAreRefused) {
    test::ScratchDir dir;
    writeText(dir / "outside.glsl", "float outside;\n");
    writeText(dir / "lib/a.glsl", "float a;\n");
    std::filesystem::create_directories(dir / "app/folder");
    for (const auto& [include, reason] : std::vector<std::pair<std::string, std::string>>{
             {"#include \"" + (dir / "lib/a.glsl").string() + "\"", "an absolute path"},
             {"#include \"../outside.glsl\"", "is outside the shader folders"},
             {"#include \"folder\"", "a folder, not a file"},
             {"#include <a.glsl>", "#include <...>"}}) {
        writeText(dir / "app/main.frag", "// main\n" + include + "\n");
        try {
            assembleShader(dir / "app/main.frag", "330 core", {}, {dir / "lib"});
            ADD_FAILURE() << include << ": expected an error";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::Runtime) << include;
            const std::string message = e.what();
            EXPECT_NE(message.find("main.frag:2: #include"), std::string::npos) << message;
            EXPECT_NE(message.find(reason), std::string::npos) << message;
        }
    }
    // A search folder's file by its name there is inside: spliced.
    writeText(dir / "app/main.frag", "#include \"a.glsl\"\n");
    EXPECT_NE(
        assembleShader(dir / "app/main.frag", "330 core", {}, {dir / "lib"}).text.find("float a;"),
        std::string::npos);
}
