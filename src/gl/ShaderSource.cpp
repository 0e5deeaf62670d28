#include "microrelief/gl/ShaderSource.h"

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <utility>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

constexpr int kMaxIncludeDepth = 32;
constexpr int kLineStride = 100000;  // line numbers per file in the assembled source

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throwRuntime(file.string() + ": cannot open shader source");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

class Assembler {
public:
    // `bundleRoot` empty: #line markers for the compiler's messages (assembleShader); else
    // one readable file for engines without an include resolver (bundleShader): a comment
    // naming each spliced file by its path from the root, no markers.
    explicit Assembler(ShaderSource& out, std::filesystem::path bundleRoot = {},
                       std::vector<std::filesystem::path> includeDirs = {})
        : out_(out), bundleRoot_(std::move(bundleRoot)), includeDirs_(std::move(includeDirs)) {}

    void splice(const std::filesystem::path& file, int depth) {
        if (depth > kMaxIncludeDepth)
            throwRuntime(file.string() + ": #include nested too deeply (a cycle?)");
        const int index = static_cast<int>(out_.files.size());
        out_.files.push_back(file);
        std::istringstream lines(readText(file));
        static const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
        std::string line;
        int number = 0;
        if (bundling()) banner("begin", file);
        lineMarker(1, index);
        while (std::getline(lines, line)) {
            ++number;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            std::smatch match;
            if (std::regex_match(line, match, include)) {
                const std::filesystem::path target = resolve(file, match[1].str());
                if (target.empty()) {
                    throwRuntime(file.string() + ":" + std::to_string(number) + ": #include \"" +
                                 match[1].str() + "\" not found");
                }
                // Each file once, as its include guard would have it anyway: the source
                // stays small however often the library's files include each other.
                if (std::find(out_.files.begin(), out_.files.end(), target) == out_.files.end()) {
                    splice(target, depth + 1);
                }
                lineMarker(number + 1, index);
                continue;
            }
            out_.text += line;
            out_.text += '\n';
        }
        if (bundling()) banner("end", file);
    }

private:
    bool bundling() const { return !bundleRoot_.empty(); }

    // The including file's folder first, then the search folders, in order; empty when
    // none holds `name`.
    std::filesystem::path resolve(const std::filesystem::path& from,
                                  const std::string& name) const {
        std::error_code ec;
        const std::filesystem::path local = (from.parent_path() / name).lexically_normal();
        if (std::filesystem::exists(local, ec)) return local;
        for (const std::filesystem::path& dir : includeDirs_) {
            const std::filesystem::path candidate = (dir / name).lexically_normal();
            if (std::filesystem::exists(candidate, ec)) return candidate;
        }
        return {};
    }

    void banner(const char* what, const std::filesystem::path& file) {
        out_.text += std::string("// ---- ") + what + " " +
                     file.lexically_relative(bundleRoot_).generic_string() + " ----\n";
    }

    // `#line L S` numbers the line after it L in source string S. Not every compiler
    // reports S (Mesa reports 0), so the file is in L too: L = index * kLineStride + line.
    void lineMarker(int line, int index) {
        if (bundling()) return;
        out_.text += "#line " + std::to_string(index * kLineStride + line) + " " +
                     std::to_string(index) + "\n";
    }

    ShaderSource& out_;
    std::filesystem::path bundleRoot_;
    std::vector<std::filesystem::path> includeDirs_;
};

}  // namespace

ShaderSource assembleShader(const std::filesystem::path& file, const std::string& version,
                            const std::vector<ShaderDefine>& defines,
                            const std::vector<std::filesystem::path>& includeDirs) {
    ShaderSource source;
    source.version = version;
    source.text = "#version " + version + "\n";
    for (const ShaderDefine& d : defines)
        source.text += "#define " + d.name + (d.value.empty() ? "" : " " + d.value) + "\n";
    Assembler(source, {}, includeDirs).splice(file.lexically_normal(), 0);
    return source;
}

std::string bundleShader(const std::filesystem::path& file, const std::filesystem::path& root,
                         const std::vector<std::filesystem::path>& includeDirs) {
    ShaderSource source;
    const std::filesystem::path start = file.lexically_normal();
    const std::filesystem::path base = root.empty() ? start.parent_path() : root.lexically_normal();
    Assembler(source, base, includeDirs).splice(start, 0);
    return source.text;
}

std::string mapCompilerLog(const std::string& log,
                           const std::vector<std::filesystem::path>& files) {
    // Mesa: "0:12(5): error: ..."; NVIDIA: "0(12) : error ..."; glslang: "ERROR: 0:12: ...".
    static const std::regex location(R"((\d+)(?::(\d+)\((\d+)\)|\((\d+)\)|:(\d+)))");
    std::string out;
    std::istringstream lines(log);
    std::string line;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_search(line, m, location)) {
            std::size_t index = std::stoul(m[1].str());
            long number = std::stol(m[2].matched   ? m[2].str()
                                    : m[4].matched ? m[4].str()
                                                   : m[5].str());
            if (number >= kLineStride) {  // the file is in the line number (see lineMarker)
                index = static_cast<std::size_t>(number / kLineStride);
                number %= kLineStride;
            }
            if (index < files.size()) {
                std::string where = files[index].string() + ":" + std::to_string(number);
                if (m[3].matched) where += ":" + m[3].str();
                line = m.prefix().str() + where + m.suffix().str();
            }
        }
        out += line + '\n';
    }
    return out;
}

}  // namespace microrelief
