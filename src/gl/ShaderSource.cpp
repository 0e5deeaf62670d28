#include "microrelief/gl/ShaderSource.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <regex>
#include <sstream>
#include <utility>

#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"

namespace microrelief {

namespace {

constexpr int kMaxIncludeDepth = 32;
constexpr int kLineStride = 100000;  // line numbers per file in the assembled source

// The whole text of a regular file of at most kMaxShaderFileBytes. Opened without
// blocking and checked on the descriptor before a byte is read: a FIFO cannot hang the
// program, a device (/dev/zero) cannot fill its memory, a folder is not read as empty
// text. Throws Error with the reason alone; the caller names the file.
std::string readShaderFile(const std::filesystem::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) throwBadInput(std::string("cannot open (") + std::strerror(errno) + ")");
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat info {};
    if (::fstat(fd, &info) != 0)
        throwBadInput(std::string("cannot read (") + std::strerror(errno) + ")");
    if (S_ISDIR(info.st_mode)) throwBadInput("a folder, not a file");
    if (!S_ISREG(info.st_mode)) throwBadInput("not a regular file (a FIFO, socket or device)");
    const std::string limit = "the " + std::to_string(kMaxShaderFileBytes) +
                              " bytes a shader source may have (ShaderSource.h)";
    if (info.st_size > kMaxShaderFileBytes)
        throwBadInput(std::to_string(info.st_size) + " bytes, more than " + limit);
    // The size, and one byte more: a file that grew since fstat is caught too.
    std::string text(static_cast<std::size_t>(info.st_size) + 1, '\0');
    std::size_t used = 0;
    while (used < text.size()) {
        const ssize_t got = ::read(fd, text.data() + used, text.size() - used);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) throwBadInput(std::string("cannot read (") + std::strerror(errno) + ")");
        if (got == 0) break;
        used += static_cast<std::size_t>(got);
    }
    if (used > static_cast<std::size_t>(kMaxShaderFileBytes))
        throwBadInput("grew past " + limit + " while read");
    text.resize(used);
    return text;
}

// `path` lies inside `root`, both canonical (absolute, links resolved, no "." or "..").
bool isWithin(const std::filesystem::path& path, const std::filesystem::path& root) {
    const std::filesystem::path relative = path.lexically_relative(root);
    return !relative.empty() && *relative.begin() != "..";
}

// The folder a file is in: "." for a bare name.
std::filesystem::path folderOf(const std::filesystem::path& file) {
    return file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
}

std::filesystem::path realPath(const std::filesystem::path& path) {
    std::error_code ec;
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(path, ec);
    return ec ? std::filesystem::absolute(path, ec).lexically_normal() : resolved;
}

// An `#include` line's file name, or why the line is no include this resolver takes:
// only `#include "relative/path"`, alone on its line.
struct IncludeLine {
    bool isInclude = false;  // the line is an #include directive, good or bad
    std::string name;        // the quoted name, when good
    std::string problem;     // why not, when bad
};

IncludeLine parseInclude(const std::string& line) {
    // [\s\S]: a CR inside the line is part of it ('.' stops at one).
    static const std::regex directive(R"(^\s*#\s*include\b([\s\S]*)$)");
    static const std::regex quoted(R"re(^\s*"([^"]*)"\s*$)re");
    std::smatch match;
    if (!std::regex_match(line, match, directive)) return {};
    const std::string rest = match[1].str();
    IncludeLine include{true, {}, {}};
    std::smatch name;
    const std::size_t first = rest.find_first_not_of(" \t");
    if (std::regex_match(rest, name, quoted)) {
        include.name = name[1].str();
        if (include.name.empty()) include.problem = "an empty file name";
    } else if (first != std::string::npos && rest[first] == '<') {
        include.problem = "#include <...> is not resolved here; write #include \"...\"";
    } else if (first != std::string::npos && rest[first] == '"' &&
               rest.find('"', first + 1) == std::string::npos) {
        include.problem = "the file name's quote is not closed";
    } else if (first != std::string::npos && rest[first] == '"') {
        include.problem = "text after the file name (#include \"file\" stands alone on its line)";
    } else {
        include.problem = "expected #include \"file\"";
    }
    return include;
}

class Assembler {
public:
    // `bundleRoot` empty: #line markers for the compiler's messages (assembleShader); else
    // one readable file for engines without an include resolver (bundleShader): a comment
    // naming each spliced file by its path from the root, no markers. Every spliced file
    // lies inside `roots` (ShaderSource.h).
    // `kind`: what a bad include is, the user's input (a file handed to the bundler) or
    // the environment's fault (the program's own shaders).
    Assembler(ShaderSource& out, ErrorKind kind, std::vector<std::filesystem::path> roots,
              std::filesystem::path bundleRoot = {},
              std::vector<std::filesystem::path> includeDirs = {})
        : out_(out),
          kind_(kind),
          bundleRoot_(std::move(bundleRoot)),
          includeDirs_(std::move(includeDirs)) {
        for (const std::filesystem::path& root : roots) roots_.push_back(realPath(root));
    }

    // The file to start from: its own errors name it alone.
    void start(const std::filesystem::path& file) {
        std::string text;
        try {
            text = readShaderFile(file);
        } catch (const Error& e) {
            throw Error(kind_, printable(file.string()) + ": " + e.what());
        }
        splice(file, text, 0);
    }

private:
    void splice(const std::filesystem::path& file, const std::string& text, int depth) {
        if (depth > kMaxIncludeDepth)
            throw Error(kind_,
                        printable(file.string()) + ": #include nested too deeply (a cycle?)");
        const int index = static_cast<int>(out_.files.size());
        out_.files.push_back(file);
        std::istringstream lines(text);
        std::string line;
        int number = 0;
        if (bundling()) banner("begin", file);
        lineMarker(1, index);
        while (std::getline(lines, line)) {
            ++number;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            const IncludeLine include = parseInclude(line);
            if (!include.isInclude) {
                out_.text += line;
                out_.text += '\n';
                continue;
            }
            // "file:line: #include "name": reason", one line whatever the file holds.
            const auto refuse = [&](const std::string& reason) {
                throw Error(kind_, printable(file.string()) + ":" + std::to_string(number) + ": " +
                                       printable(line.substr(line.find('#'))) + ": " + reason);
            };
            if (!include.problem.empty()) refuse(include.problem);
            const std::filesystem::path target = resolve(file, include.name, refuse);
            // Each file once, as its include guard would have it anyway: the source
            // stays small however often the library's files include each other.
            if (std::find(out_.files.begin(), out_.files.end(), target) == out_.files.end()) {
                std::string included;
                try {
                    included = readShaderFile(target);
                } catch (const Error& e) {
                    refuse(e.what());
                }
                splice(target, included, depth + 1);
            }
            lineMarker(number + 1, index);
        }
        if (bundling()) banner("end", file);
    }

    bool bundling() const { return !bundleRoot_.empty(); }

    // The including file's folder first, then the search folders, in order: the first
    // that holds `name`. A name that is absolute, or that leads out of every root
    // (through ".." or a symbolic link), is refused, not looked up further.
    template <class Refuse>
    std::filesystem::path resolve(const std::filesystem::path& from, const std::string& name,
                                  const Refuse& refuse) const {
        if (name.find_first_of(std::string("\0", 1) + "\\") != std::string::npos ||
            printable(name) != name)
            refuse("control characters or a backslash in the file name");
        const std::filesystem::path relative(name);
        if (relative.is_absolute())
            refuse(
                "an absolute path (a name is relative to the including file's folder or a "
                "search folder)");
        std::vector<std::filesystem::path> folders{folderOf(from)};
        folders.insert(folders.end(), includeDirs_.begin(), includeDirs_.end());
        for (const std::filesystem::path& folder : folders) {
            const std::filesystem::path candidate = (folder / relative).lexically_normal();
            std::error_code ec;
            if (!std::filesystem::exists(candidate, ec)) continue;
            const std::filesystem::path real = realPath(candidate);
            if (std::none_of(roots_.begin(), roots_.end(),
                             [&](const auto& root) { return isWithin(real, root); })) {
                refuse(printable(real.string()) + " is outside the shader folders (" + rootList() +
                       ")");
            }
            return candidate;
        }
        refuse("not found (looked in " + folderList(folders) + ")");
        return {};
    }

    static std::string folderList(const std::vector<std::filesystem::path>& folders) {
        std::string list;
        for (const auto& folder : folders)
            list += (list.empty() ? "" : ", ") + printable(folder.empty() ? "." : folder.string());
        return list;
    }
    std::string rootList() const { return folderList(roots_); }

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
    ErrorKind kind_;
    std::vector<std::filesystem::path> roots_;  // canonical
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
    const std::filesystem::path start = file.lexically_normal();
    std::vector<std::filesystem::path> roots{folderOf(start)};
    roots.insert(roots.end(), includeDirs.begin(), includeDirs.end());
    Assembler(source, ErrorKind::Runtime, roots, {}, includeDirs).start(start);
    return source;
}

std::string bundleShader(const std::filesystem::path& file, const std::filesystem::path& root,
                         const std::vector<std::filesystem::path>& includeDirs) {
    ShaderSource source;
    const std::filesystem::path start = file.lexically_normal();
    const std::filesystem::path base = root.empty() ? folderOf(start) : root.lexically_normal();
    if (!isWithin(realPath(start), realPath(base))) {
        throwBadInput(printable(file.string()) + ": not inside the root " +
                      printable(base.string()) + " its includes are taken from");
    }
    std::vector<std::filesystem::path> roots{base};
    roots.insert(roots.end(), includeDirs.begin(), includeDirs.end());
    Assembler(source, ErrorKind::BadInput, roots, base, includeDirs).start(start);
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
