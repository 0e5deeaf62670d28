// microrelief-glsl-bundle held to the bundlers' table of cases (tests/bundler/cases.txt),
// which microrelief-three's scripts/build.mjs is held to as well (build_cases.mjs): one
// named test a case. The table says what each case is and how it is run.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "TestSupport.h"

using namespace microrelief;

namespace {

// "\n", "\r", "\t", "\\" and "\xHH" in the table's values.
std::string unescape(const std::string& text) {
    std::string out;
    for (std::size_t k = 0; k < text.size(); ++k) {
        if (text[k] != '\\' || k + 1 == text.size()) {
            out += text[k];
            continue;
        }
        const char c = text[++k];
        if (c == 'n')
            out += '\n';
        else if (c == 'r')
            out += '\r';
        else if (c == 't')
            out += '\t';
        else if (c == 'x' && k + 2 < text.size()) {
            out += static_cast<char>(std::stoi(text.substr(k + 1, 2), nullptr, 16));
            k += 2;
        } else
            out += c;
    }
    return out;
}

// A block of the table: its name ("tree" for the tree) and its keys' values, in order.
struct Block {
    std::string name;
    std::vector<std::pair<std::string, std::string>> keys;

    std::vector<std::string> all(const std::string& key) const {
        std::vector<std::string> values;
        for (const auto& [k, v] : keys)
            if (k == key) values.push_back(v);
        return values;
    }
    std::string get(const std::string& key, const std::string& otherwise = "") const {
        const auto values = all(key);
        return values.empty() ? otherwise : values.front();
    }
};

// gtest names a failing run's parameter: the case's name.
void PrintTo(const Block& block, std::ostream* out) {
    *out << block.name;
}

std::vector<Block> readTable() {
    std::ifstream in(MICRORELIEF_BUNDLER_CASES);
    std::vector<Block> blocks;
    bool open = false;
    for (std::string line; std::getline(in, line);) {
        if (line.empty()) {
            open = false;
            continue;
        }
        if (line[0] == '#') continue;
        const std::size_t space = line.find(' ');
        const std::string key = line.substr(0, space);
        const std::string value =
            space == std::string::npos ? "" : unescape(line.substr(space + 1));
        if (!open) {
            blocks.push_back({key == "case" ? value : key, {}});
            open = true;
        } else {
            blocks.back().keys.emplace_back(key, value);
        }
    }
    return blocks;
}

const std::vector<Block>& table() {
    static const std::vector<Block> blocks = readTable();
    return blocks;
}

std::vector<Block> cases() {
    std::vector<Block> found;
    for (const Block& b : table())
        if (b.name != "tree") found.push_back(b);
    return found;
}

// The tree block's files, links, FIFOs and holes, under `root`.
void makeTree(const std::filesystem::path& root) {
    namespace fs = std::filesystem;
    for (const Block& b : table()) {
        if (b.name != "tree") continue;
        for (const auto& [kind, value] : b.keys) {
            const std::size_t space = value.find(' ');
            const fs::path file = root / value.substr(0, space);
            const std::string rest = space == std::string::npos ? "" : value.substr(space + 1);
            fs::create_directories(file.parent_path());
            if (kind == "file") {
                std::ofstream(file, std::ios::binary) << rest;
            } else if (kind == "link") {
                fs::create_symlink(rest, file);
            } else if (kind == "fifo") {
                ASSERT_EQ(::mkfifo(file.c_str(), 0600), 0) << file;
            } else if (kind == "sparse") {
                std::ofstream(file, std::ios::binary).close();
                fs::resize_file(file, std::stoull(rest));
            } else {
                FAIL() << "cases.txt: unknown tree entry '" << kind << "'";
            }
        }
    }
}

std::size_t count(const std::string& text, const std::string& part) {
    std::size_t n = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1))
        ++n;
    return n;
}

class BundlerCases : public ::testing::TestWithParam<Block> {
protected:
    test::ScratchDir dir;
};

TEST_P(BundlerCases, GlslBundle) {
    namespace fs = std::filesystem;
    const Block& c = GetParam();
    makeTree(dir.path());
    const fs::path entry = dir / "shaders/microrelief/multilevel_trace.glsl";
    std::string text = "// main\n" + c.get("include") + "\n";
    if (!c.get("padding").empty())
        text += "#define MICRORELIEF_PADDING " + std::string(std::stoul(c.get("padding")), '.') + "\n";
    std::ofstream(entry, std::ios::binary) << text << "void main() {" << c.get("main") << "}\n";
    const fs::path out = dir / c.get("out.bundle", "out/bundle.glsl");
    fs::create_directories(out.parent_path());
    const std::string command = std::string("timeout 20 ") + MICRORELIEF_GLSL_BUNDLE_EXE + " " +
                                entry.string() + " --root " + (dir / "shaders").string() + " -I " +
                                (dir / "shaders").string() + " --out " + out.string();
    std::map<std::string, std::vector<std::uint8_t>> before;
    for (const std::string& file : c.all("unchanged")) before[file] = test::readBytes(dir / file);

    const int status = std::stoi(c.get("status", "0"));
    test::RunResult r;
    std::vector<std::uint8_t> last;
    if (const std::string limit = c.get("file-size-limit"); !limit.empty()) {
        // The premise: unlimited, the output is written and larger than the limit.
        const test::RunResult whole = test::runCommand(command, dir.path());
        ASSERT_EQ(whole.status, 0) << whole.err;
        ASSERT_GT(fs::file_size(out), std::stoull(limit));
        last = test::readBytes(out);
        r = test::runCommandWithFileSizeLimit(command, std::stoull(limit));
    } else {
        r = test::runCommand(command, dir.path());
    }
    if (status == 0) {
        ASSERT_EQ(r.status, 0) << r.err;
        const std::string bundled = test::readText(out);
        for (const std::string& part : c.all("contains"))
            EXPECT_NE(bundled.find(part), std::string::npos) << part << "\n" << bundled;
        for (const std::string& part : c.all("once"))
            EXPECT_EQ(count(bundled, part), 1u) << part << "\n" << bundled;
    } else {
        test::expectOneLineFailure(r, "microrelief-glsl-bundle", status, c.get("reason"));
        if (!c.get("at").empty()) {
            EXPECT_NE(r.err.find(c.get("at")), std::string::npos) << r.err;
        }
        EXPECT_EQ(r.err.find('\r'), std::string::npos) << "a raw CR in the message";
        EXPECT_EQ(r.err.find('\x01'), std::string::npos) << "a raw control character";
        if (!last.empty()) {
            EXPECT_EQ(test::readBytes(out), last) << "the last output changed";
        } else if (c.all("unchanged").empty()) {
            EXPECT_FALSE(fs::exists(out)) << "a refused run wrote " << out;
        }
        EXPECT_EQ(test::hiddenFilesIn(out.parent_path()), std::vector<std::string>{});
    }
    for (const auto& [file, bytes] : before) EXPECT_EQ(test::readBytes(dir / file), bytes) << file;
}

INSTANTIATE_TEST_SUITE_P(Table, BundlerCases, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Block>& info) {
                             return info.param.name;
                         });

// The table is read: a case a runner skipped would pass unseen.
TEST(BundlerTable, HoldsTheTreeAndTheCases) {
    EXPECT_GE(cases().size(), 25u);
    EXPECT_TRUE(std::any_of(table().begin(), table().end(),
                            [](const Block& b) { return b.name == "tree"; }));
}

}  // namespace
