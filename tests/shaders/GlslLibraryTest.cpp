// The reusable GLSL library (shaders/microrelief/) must be a pure function library that
// compiles as GLSL 3.30 core and GLSL ES 3.00 (and 4.00 core, where it gathers): each file is
// checked on its own by glslangValidator (Debian glslang-tools), wrapped in a minimal fragment
// shader, the way another engine would include it. The app's own shaders are checked as 3.30.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "TestSupport.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/core/base/BaseType.h"
#include "microrelief/gl/PagedPyramid.h"
#include "microrelief/gl/ShaderSource.h"

using namespace microrelief;

namespace {

const std::filesystem::path kShaders = MICRORELIEF_SHADER_SOURCE_DIR;

std::vector<std::filesystem::path> libraryFiles() {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(kShaders / "microrelief")) {
        if (entry.path().extension() == ".glsl") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// A wrapper's include of a library file the way an engine writes it: by its name under
// the shader folder, which goes to assembleShader as a search folder (an absolute
// include is refused).
std::string includeOf(const std::filesystem::path& libraryFile) {
    return "#include \"microrelief/" + libraryFile.filename().string() + "\"\n";
}

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Runs glslangValidator on an assembled source; returns its output, empty on success.
// With `tree`, the intermediate tree it prints on success goes there.
std::string validate(const test::ScratchDir& dir, const ShaderSource& source,
                     const std::string& stage, const std::string& name,
                     std::string* tree = nullptr) {
    const std::filesystem::path file = dir / (name + "." + stage);
    std::ofstream(file) << source.text;
    const std::filesystem::path log = dir / (name + ".log");
    const std::string command = std::string(GLSLANG_VALIDATOR) + (tree ? " -i " : " ") +
                                file.string() + " > " + log.string() + " 2>&1";
    const int status = std::system(command.c_str());
    if (tree) *tree = readText(log);
    return status == 0 ? std::string() : mapCompilerLog(readText(log), source.files);
}

// The lines of glslang's intermediate tree that run below highp ("mediump", "lowp"): the
// first few and how many there are; empty when there are none.
std::string belowHighp(const std::string& tree) {
    std::istringstream lines(tree);
    std::string line, found;
    int count = 0;
    while (std::getline(lines, line)) {
        if (line.find("mediump") == std::string::npos && line.find("lowp") == std::string::npos)
            continue;
        if (++count <= 4) found += line + "\n";
    }
    return count == 0 ? "" : std::to_string(count) + " lines below highp, first:\n" + found;
}

// No precision prelude for ES: the library states what it needs itself (precision.glsl),
// and the ES check holds it to that (EveryFileRunsAtHighpUnderGlslEs).
const char* const kDialects[] = {"330 core", "400 core" /* the textureGather path */, "300 es"};

}  // namespace

TEST(GlslLibrary, EveryFileCompilesAloneAsGlsl330And400AndEs300) {
    test::ScratchDir dir;
    const auto files = libraryFiles();
    ASSERT_GE(files.size(), 5u);
    for (const auto& file : files) {
        for (const char* version : kDialects) {
            const std::filesystem::path wrapper = dir / ("use_" + file.stem().string() + ".frag");
            std::ofstream(wrapper)
                << includeOf(file)
                << "out vec4 fragColor;\nvoid main() { fragColor = vec4(1.0); }\n";
            const ShaderSource source = assembleShader(wrapper, version, {}, {kShaders});
            const std::string errors = validate(dir, source, "frag", file.stem().string());
            EXPECT_TRUE(errors.empty()) << file.filename() << " as GLSL " << version << ":\n"
                                        << errors;
        }
    }
}

// The read hooks (texture_reads.glsl) let a host read its own way without forking a file:
// the tracers, the shadows and a step-based peer compile with every texture a layer of a
// texture array, read only through the host's macros (docs/engine.md's example).
TEST(GlslLibrary, ReadHooksLetAHostReadTextureArrays) {
    test::ScratchDir dir;
    for (const char* version : {"400 core", "300 es"}) {
        for (const char* tracer :
             {"multilevel_trace", "maxmip_trace", "shadow", "relief_mapping"}) {
            const std::filesystem::path wrapper = dir / (std::string("arrays_") + tracer + ".frag");
            std::ofstream(wrapper)
                << "#define MICRORELIEF_SAMPLER sampler2DArray\n"
                << "#define MICRORELIEF_READ_SAMPLE(t, p) texelFetch(t, ivec3(p, reliefLayer), "
                   "0).r\n"
                << "#define MICRORELIEF_GATHER_SAMPLES(t, uv) textureGather(t, vec3(uv, "
                   "float(reliefLayer)))\n"
                << "#define MICRORELIEF_READ_PYRAMID(t, p, level, size) texelFetch(t, ivec3(p, "
                   "reliefLayer), level).r\n"
                << "#ifdef GL_ES\nprecision highp sampler2DArray;\nprecision highp int;\n#endif\n"
                << "uniform int reliefLayer;\n"
                << includeOf(kShaders / "microrelief" / (std::string(tracer) + ".glsl"))
                << "uniform sampler2DArray windows, heights;\nout vec4 fragColor;\n"
                << "void main() {\n"
                << "    mr_Relief relief = mr_Relief(mr_ReliefMap(vec2(64.0), ivec2(64), 7, 1.0, "
                   "ivec2(1)),\n"
                << "        mr_ReliefPlacement(mat4(1.0), mat4(1.0), 0.1, vec3(1.0)));\n"
                << "    vec3 o = vec3(gl_FragCoord.xy, 2.0), d = vec3(0.3, 0.2, -1.0);\n"
                << (std::string(tracer) == "relief_mapping"
                        ? "    mr_ReliefHit hit = mr_traceReliefMapping(relief, heights, o, d, 32, "
                          "8);\n"
                    : std::string(tracer) == "maxmip_trace"
                        ? "    mr_ReliefHit hit = mr_traceMaxMip(relief, "
                          "mr_closestHitQuery(relief.map), "
                          "windows, heights, o, d);\n"
                        : "    mr_ReliefHit hit = mr_traceMultilevel(relief, "
                          "mr_closestHitQuery(relief.map), "
                          "windows, heights, o, d);\n")
                << (std::string(tracer) == "shadow"
                        ? "    bool out_ = false;\n    float lit = mr_hardShadow(relief, windows, "
                          "heights, hit, "
                          "vec3(0.2, 0.1, 1.0), MR_T_INFINITY, out_);\n"
                        : "    float lit = 1.0;\n")
                << "    fragColor = vec4(hit.position, lit);\n}\n";
            const ShaderSource source = assembleShader(wrapper, version, {}, {kShaders});
            const std::string errors =
                validate(dir, source, "frag", std::string("arrays_") + tracer);
            EXPECT_TRUE(errors.empty()) << tracer << " as GLSL " << version << ":\n" << errors;
        }
    }
}

TEST(GlslLibrary, LibraryFilesAreFunctionLibraries) {
    // No #version, no uniforms, no in/out at file scope; a file-named include guard.
    // File scope only (unindented): an indented "out" is a function parameter.
    const std::regex forbidden(R"(^(#\s*version|uniform\s|in\s|out\s|layout\s*\())");
    for (const auto& file : libraryFiles()) {
        std::istringstream lines(readText(file));
        std::string line;
        int number = 0;
        while (std::getline(lines, line)) {
            ++number;
            EXPECT_FALSE(std::regex_search(line, forbidden))
                << file.filename() << ":" << number << ": " << line;
        }
        std::string guard = "MICRORELIEF_" + file.stem().string() + "_GLSL";
        std::transform(guard.begin(), guard.end(), guard.begin(), ::toupper);
        EXPECT_NE(readText(file).find("#ifndef " + guard), std::string::npos)
            << file.filename() << " lacks " << guard;
    }
}

// The single-file tracers the build makes for engines without an include resolver
// (share/microrelief/shaders/single/): no #include and no #line left, and each compiles
// pasted after a bare #version, as 3.30, 4.00 and ES 3.00.
TEST(GlslLibrary, SingleFileTracersCompileWithoutAResolver) {
    test::ScratchDir dir;
    int count = 0;
    for (const auto& entry : std::filesystem::directory_iterator(MICRORELIEF_SINGLE_GLSL_DIR)) {
        const std::string text = readText(entry.path());
        ++count;
        EXPECT_EQ(text.find("#include"), std::string::npos) << entry.path().filename();
        EXPECT_EQ(text.find("#line"), std::string::npos) << entry.path().filename();
        for (const char* version : kDialects) {
            const std::filesystem::path file =
                dir / ("single_" + entry.path().stem().string() + ".frag");
            std::ofstream(file) << "#version " << version << "\n"
                                << text
                                << "out vec4 fragColor;\nvoid main() { fragColor = vec4(1.0); }\n";
            const std::string command = std::string(GLSLANG_VALIDATOR) + " " + file.string() +
                                        " > " + (dir / "single.log").string() + " 2>&1";
            EXPECT_EQ(std::system(command.c_str()), 0)
                << entry.path().filename() << " as GLSL " << version << ":\n"
                << readText(dir / "single.log");
        }
    }
    EXPECT_EQ(count, 9);  // every tracer: multilevel, maxmip and the seven peers (cone, rcsm)
}

// Names that cannot collide with an engine's own (glslify, LYGIA): every function the
// library defines (as glslang's tree lists them: "Function Definition: name("), and every
// struct, constant and macro at file scope, carries the prefix: mr_ for functions,
// structs and types, MR_ for constants, MICRORELIEF_ for option macros.
TEST(GlslLibrary, EveryPublicNameCarriesThePrefix) {
    test::ScratchDir dir;
    const std::regex function(R"(Function Definition: (\w+)\()");
    const std::regex declaration(
        R"(^(?:struct\s+(\w+)|const\s+\w+\s+(\w+)\s*=|#\s*define\s+(\w+)))");
    int functions = 0;
    for (const auto& file : libraryFiles()) {
        const std::filesystem::path wrapper = dir / ("names_" + file.stem().string() + ".frag");
        std::ofstream(wrapper) << includeOf(file)
                               << "out vec4 fragColor;\nvoid main() { fragColor = vec4(1.0); }\n";
        std::string tree;
        ASSERT_EQ(validate(dir, assembleShader(wrapper, "330 core", {}, {kShaders}), "frag",
                           file.stem().string(), &tree),
                  "");
        for (std::sregex_iterator it(tree.begin(), tree.end(), function), end; it != end; ++it) {
            const std::string name = (*it)[1];
            if (name == "main") continue;
            ++functions;
            EXPECT_EQ(name.rfind("mr_", 0), 0u) << file.filename() << ": function " << name;
        }
        std::istringstream lines(readText(file));
        std::string line;
        while (std::getline(lines, line)) {
            std::smatch m;
            if (!std::regex_search(line, m, declaration)) continue;
            if (m[1].matched) {
                EXPECT_EQ(m[1].str().rfind("mr_", 0), 0u) << file.filename() << ": " << line;
            }
            if (m[2].matched) {
                EXPECT_EQ(m[2].str().rfind("MR_", 0), 0u) << file.filename() << ": " << line;
            }
            // A macro is an option (MICRORELIEF_), a type chosen by one (mr_ReliefPatch), or
            // a constant an #if compares an option with (MR_, as the constants: variants.glsl).
            if (m[3].matched) {
                EXPECT_TRUE(m[3].str().rfind("MICRORELIEF_", 0) == 0 ||
                            m[3].str().rfind("mr_", 0) == 0 || m[3].str().rfind("MR_", 0) == 0)
                    << file.filename() << ": " << line;
            }
        }
    }
    EXPECT_GT(functions, 100);  // the tree was read: the library defines many
}

// GLSL ES 3.00 fragment shaders default int to mediump, which holds +-2^15 only, and
// sampler2D to lowp: the 24-bit segment indices and the R32F texels need highp. Every
// file, compiled as ES with no precision of the host's, must run at highp throughout:
// no operation, variable or texture read below it in glslang's intermediate tree.
TEST(GlslLibrary, EveryFileRunsAtHighpUnderGlslEs) {
    test::ScratchDir dir;
    for (const auto& file : libraryFiles()) {
        const std::filesystem::path wrapper = dir / ("es_" + file.stem().string() + ".frag");
        std::ofstream(wrapper) << includeOf(file)
                               << "out vec4 fragColor;\nvoid main() { fragColor = vec4(1.0); }\n";
        std::string tree;
        const std::string errors = validate(dir, assembleShader(wrapper, "300 es", {}, {kShaders}),
                                            "frag", file.stem().string(), &tree);
        ASSERT_TRUE(errors.empty()) << file.filename() << ":\n" << errors;
        EXPECT_EQ(belowHighp(tree), "") << file.filename();
    }
}

// The program's own shaders, every method of relief.frag, as GLSL 3.30 and 4.00 core and
// as GLSL ES 3.00 (there at highp throughout, as above).
TEST(GlslLibrary, AppShadersCompileAsGlsl330And400AndEs300) {
    test::ScratchDir dir;
    for (const char* version : {"330 core", "400 core", "300 es"}) {
        for (int method = 0; method < glsl::kMethodCount; ++method) {
            for (const char* name : {"relief_box.vert", "relief.frag"}) {
                const std::filesystem::path file = kShaders / name;
                const ShaderSource source =
                    assembleShader(file, version, {{"MICRORELIEF_METHOD", std::to_string(method)}});
                const std::string stage = file.extension().string().substr(1);
                std::string tree;
                const std::string errors =
                    validate(dir, source, stage, file.stem().string(), &tree);
                EXPECT_TRUE(errors.empty())
                    << name << " (method " << method << ") as GLSL " << version << ":\n"
                    << errors;
                if (std::string(version) == "300 es" && stage == "frag") {
                    EXPECT_EQ(belowHighp(tree), "") << name << " (method " << method << ")";
                }
            }
        }
    }
}

// The paged variant (shaders/paged_map.glsl, gl/PagedPyramid.h), GLSL 4.30 core: on
// every base, with either last level and soft shadows, its layout given as the host gives it.
TEST(GlslLibrary, PagedVariantCompilesAsGlsl430) {
    test::ScratchDir dir;
    for (int base = 0; base <= 2; ++base) {
        for (int interpolation = 0; interpolation <= 1; ++interpolation) {
            const std::vector<ShaderDefine> defines = {
                {"MICRORELIEF_BASE", std::to_string(base)},
                {"MICRORELIEF_INTERPOLATION", std::to_string(interpolation)},
                {"MICRORELIEF_SHADOWS", "2"},
                {"MICRORELIEF_PAGED", "1"},
                {"MICRORELIEF_PAGE_INFO_AT", std::to_string(PageTableLayout::kInfoAt)},
                {"MICRORELIEF_PAGE_LEVELS_AT", std::to_string(PageTableLayout::kLevelsAt)},
                {"MICRORELIEF_PAGE_ENTRIES_AT", std::to_string(PageTableLayout::kEntriesAt)}};
            const std::string errors =
                validate(dir, assembleShader(kShaders / "relief.frag", "430 core", defines), "frag",
                         "relief");
            EXPECT_TRUE(errors.empty()) << "paged relief.frag, base " << base << ", interpolation "
                                        << interpolation << ":\n"
                                        << errors;
        }
    }
}

// Each row of the table of bases (core/base/BaseType.h) names the file base_surface.glsl
// chooses for its kind: `#if`/`#elif MICRORELIEF_BASE == MR_BASE_NAME` (the kind's value by
// its name in variants.glsl, core/GlslConstants.h) then its #include, or the `#else`
// branch's for a kind the choice does not list.
TEST(GlslLibrary, EveryBaseRowsFileIsTheChoiceForItsKind) {
    const std::string text = readText(kShaders / "microrelief" / "base_surface.glsl");
    const std::regex branch(
        "#\\s*(?:el)?if\\s+MICRORELIEF_BASE\\s*==\\s*MR_BASE_(\\w+)\\s*\\n\\s*#\\s*include\\s+"
        "\"([^\"]+)\"");
    const std::regex otherwise("#\\s*else\\s*\\n\\s*#\\s*include\\s+\"(base_[^\"]+)\"");
    std::map<int, std::string> chosen;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), branch);
         it != std::sregex_iterator(); ++it) {
        std::string name = (*it)[1];
        for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        const auto member =
            std::find_if(std::begin(glsl::kBaseKindValues), std::end(glsl::kBaseKindValues),
                         [&](const glsl::EnumMember& m) { return m.name == name; });
        ASSERT_NE(member, std::end(glsl::kBaseKindValues))
            << "MR_BASE_" << (*it)[1] << " (base_surface.glsl) is none of variants.glsl's";
        chosen[member->value] = (*it)[2];
    }
    EXPECT_FALSE(chosen.empty())
        << "no #if MICRORELIEF_BASE == MR_BASE_... read in base_surface.glsl";
    std::smatch fallback;
    ASSERT_TRUE(std::regex_search(text, fallback, otherwise))
        << "base_surface.glsl has no #else base";
    for (const BaseType& type : baseTypes()) {
        const int kind = static_cast<int>(type.kind);
        const std::string file = chosen.count(kind) ? chosen[kind] : fallback[1].str();
        EXPECT_EQ(file, type.shaderFile) << type.name << " (MICRORELIEF_BASE " << kind
                                         << "): base_surface.glsl chooses " << file;
        EXPECT_TRUE(std::filesystem::is_regular_file(kShaders / "microrelief" / type.shaderFile))
            << type.shaderFile;
    }
}

// Every base surface of the table and last level the renderer builds (MICRORELIEF_BASE,
// MICRORELIEF_INTERPOLATION 0..1): the app's fragment shader as 3.30 and 4.00, and the
// library's entry point as an engine or a browser would include it, as ES 3.00.
TEST(GlslLibrary, EveryBaseAndInterpolationCompiles) {
    test::ScratchDir dir;
    std::set<int> kinds;
    for (const BaseType& type : baseTypes()) kinds.insert(static_cast<int>(type.kind));
    for (int base : kinds) {
        for (int interpolation = 0; interpolation <= 1; ++interpolation) {
            const std::vector<ShaderDefine> defines = {
                {"MICRORELIEF_BASE", std::to_string(base)},
                {"MICRORELIEF_INTERPOLATION", std::to_string(interpolation)}};
            const std::string variant =
                "base " + std::to_string(base) + ", interpolation " + std::to_string(interpolation);
            for (const char* version : {"330 core", "400 core"}) {
                const ShaderSource source =
                    assembleShader(kShaders / "relief.frag", version, defines);
                const std::string errors = validate(dir, source, "frag", "relief");
                EXPECT_TRUE(errors.empty())
                    << "relief.frag, " << variant << ", " << version << ":\n"
                    << errors;
            }
            const char* es = kDialects[2];  // the library states its own precision
            const std::filesystem::path wrapper = dir / "use_relief_hit.frag";
            std::ofstream(wrapper)
                << includeOf(kShaders / "microrelief" / "relief_hit.glsl")
                << "out vec4 fragColor;\nvoid main() { fragColor = vec4(1.0); }\n";
            const std::string errors = validate(
                dir, assembleShader(wrapper, es, defines, {kShaders}), "frag", "relief_hit");
            EXPECT_TRUE(errors.empty()) << "relief_hit.glsl as ES 3.00, " << variant << ":\n"
                                        << errors;
        }
    }
}

// The GPU pyramid builder's passes (shaders/pyramid/, gl/PyramidBuilder.h), the height
// edits' (shaders/edit/: the brush, the animated fields) and the web page's own
// (shaders/web/): GLSL 3.30 core as the library compiles them, and as they stand as GLSL
// ES 3.00 (the WebGL 2 page, web/, runs the pyramid passes and its own), there at highp
// throughout: the bound's integer arithmetic needs 32-bit uints.
TEST(GlslLibrary, PyramidAndEditPassesCompileAsGlsl330AndEs300) {
    test::ScratchDir dir;
    int count = 0;
    std::vector<std::filesystem::path> files;
    for (const char* folder : {"pyramid", "edit", "web"})
        for (const auto& entry : std::filesystem::directory_iterator(kShaders / folder))
            files.push_back(entry.path());
    for (const std::filesystem::path& path : files) {
        const std::filesystem::directory_entry entry(path);
        const std::string stage = entry.path().extension().string().substr(1);
        ++count;
        for (const char* version : {"330 core", "300 es"}) {
            const ShaderSource source = assembleShader(entry.path(), version, {}, {kShaders});
            std::string tree;
            const std::string errors =
                validate(dir, source, stage, entry.path().stem().string(), &tree);
            EXPECT_TRUE(errors.empty())
                << entry.path().filename() << " as GLSL " << version << ":\n"
                << errors;
            if (std::string(version) == "300 es" && stage == "frag") {
                EXPECT_EQ(belowHighp(tree), "") << entry.path().filename();
            }
        }
    }
    // The triangle, the finest windows (at once, and from a band's bounds), the finest
    // bounds, the coarser windows and aligned levels, cone's cone map; the brush, the
    // fields; the page's presentation.
    EXPECT_EQ(count, 10);
}
