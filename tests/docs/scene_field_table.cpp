// scene_field_table: docs/cli.md's table of scene options, written from the library's table
// of scene fields (core/scene/SceneFields.h) and of bases (core/base/BaseType.h), and the
// check that the committed page holds exactly that table (ctest docs.cli_table).
//
//   scene_field_table print              the table, Markdown, on stdout
//   scene_field_table check FILE.md      exit 1, saying how to regenerate, where FILE's
//                                        table differs
//   scene_field_table write FILE.md      replace FILE's table with the generated one
//   scene_field_table keys SOURCE_DIR    exit 1 where the pages' URL keys (web/scene.js,
//                                        examples/three/view.js) are not the rows' and the
//                                        pages' own (tests/web/page_keys.txt; ctest
//                                        web.field_keys)
//
// The table sits between two marker lines (kBegin, kEnd); the rest of the page is prose.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "microrelief/core/base/BaseType.h"
#include "microrelief/core/scene/SceneFields.h"

namespace {

using namespace microrelief;

constexpr const char* kBegin =
    "<!-- scene options: generated from src/core/scene/SceneFields.cpp by "
    "tests/docs/scene_field_table.cpp (cmake --build build --target docs-cli-table); "
    "edit the rows there -->";
constexpr const char* kEnd = "<!-- end of the generated scene options -->";
constexpr const char* kRegenerate = "cmake --build build --target docs-cli-table";

std::string cell(std::string_view text) {
    return text.empty() ? std::string() : std::string(text);
}

std::string row(const std::string& option, const std::string& key, const std::string& defaults,
                const std::string& range, const std::string& meaning) {
    return "| " + option + " | " + (key.empty() ? "" : "`" + key + "`") + " | " + defaults + " | " +
           range + " | " + meaning + " |\n";
}

// A size of the bases, one row for its field ("--radius R | 0.3 (cylinder), 0.5 (sphere)").
std::string baseSizeRow(const std::string& field) {
    std::string value, defaults, owners, label;
    for (const BaseType& type : baseTypes()) {
        for (const BaseSize& size : type.sizes) {
            if (size.field != field) continue;
            double numbers[3] = {};
            size.read(type.defaults, numbers);
            std::ostringstream text;
            for (int i = 0; i < size.count; ++i) text << (i ? "," : "") << numbers[i];
            defaults += (defaults.empty() ? "" : ", ") + text.str() + " (" + type.name + ")";
            owners += (owners.empty() ? "the " : " or the ") + std::string(type.name);
            label = size.label;
            value = size.count == 3 ? "x,y,z" : std::string(1, label.front());
        }
    }
    for (char& c : label) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    // The page's key for a size is its flag's name (web/scene.js: radius, length, radii).
    const std::string flag = sceneFieldFlag(field);
    return row("`" + flag + " " + value + "`", flag.substr(2), defaults, "world units, > 0",
               "the " + label + (value == "x,y,z" ? " along x, y, z" : "") + " of " + owners +
                   " (`--base`)");
}

std::string generatedTable() {
    std::string table = std::string(kBegin) + "\n\n";
    table += "| option | page key | default | range, unit | meaning |\n|---|---|---|---|---|\n";
    for (const SceneField& field : sceneFieldTable()) {
        if (field.flag.empty()) continue;  // a library user's only (map.samples)
        std::string option = std::string(field.flag);
        if (!field.valueName.empty()) option += " " + std::string(field.valueName);
        table += row("`" + option + "`", cell(field.urlKey), cell(field.defaultText),
                     cell(field.range), cell(field.doc.empty() ? field.help : field.doc));
        if (field.path == "base")
            for (const std::string& size : baseSizeFields()) table += baseSizeRow(size);
    }
    return table + "\n" + kEnd + "\n";
}

bool read(const std::string& path, std::string& text) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream all;
    all << in.rdbuf();
    text = all.str();
    return true;
}

// Where the generated table lies in `text`: [begin, end) covering both markers' lines.
bool findTable(const std::string& text, std::size_t& begin, std::size_t& end) {
    begin = text.find(kBegin);
    const std::size_t close = text.find(kEnd);
    if (begin == std::string::npos || close == std::string::npos || close < begin) return false;
    end = close + std::string(kEnd).size();
    if (end < text.size() && text[end] == '\n') ++end;
    return true;
}

int fail(const std::string& message) {
    std::cerr << "scene_field_table: " << message << "\n";
    return 1;
}

// A page whose URL keys are held to the table, and how much of it the page takes.
struct Page {
    const char* path;  // from the source folder
    // The whole table: the page reads (viewFromQuery: get('key', ...)) and writes
    // (queryFromView: q.set('key', ...)) every key of it. Else the page reads some keys
    // (get('key', ...)), none outside the table.
    bool whole;
};
constexpr Page kPages[] = {{"web/scene.js", true}, {"examples/three/view.js", false}};
constexpr const char* kPageKeysFile = "tests/web/page_keys.txt";
// A key the page reads (get('eye', ...)) and one it writes (q.set('eye', ...)).
constexpr const char* kReadKey = R"(\bget\('([a-z][a-z-]*)')";
constexpr const char* kWrittenKey = R"(\bq\.set\('([a-z][a-z-]*)')";
// A page that takes the bases' sizes from the browser's table of bases (web/relief_core.js's
// kBaseSizes, or the package's copy of it, generated from the rows this program's baseSizeFields() reads, and held to
// them by ctest web.core) reads (get(size.key, ...)) and writes (q.set(size.key, ...)) every
// size's key in one loop.
constexpr const char* kCoreSizes =
    R"(import \{[^}]*\bkBaseSizes\b[^}]*\} from '\./(node_modules/microrelief-three/generated/)?relief_core\.js')";
constexpr const char* kReadSizes = "get(size.key,";
constexpr const char* kWrittenSizes = "q.set(size.key,";

// Every key `pattern`'s first group matches in `text`.
std::set<std::string> matches(const std::string& text, const char* pattern) {
    std::set<std::string> keys;
    const std::regex expression(pattern);
    for (auto m = std::sregex_iterator(text.begin(), text.end(), expression);
         m != std::sregex_iterator(); ++m)
        keys.insert((*m)[1].str());
    return keys;
}

// The keys that are a page's own, no scene field's (resolution, clean, ...), by page, from
// tests/web/page_keys.txt: a page, a key and why, a line; '#' starts a comment line.
// tests/web/check_url_keys.py (ctest web.keys) reads the same list. False, with `error`
// set, where a line is not one.
bool readPageKeys(const std::string& text, std::map<std::string, std::set<std::string>>& own,
                  std::string& error) {
    std::istringstream lines(text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
        std::istringstream fields(line);
        std::string path, key, why;
        if (!(fields >> path) || path.front() == '#') continue;
        const bool known = std::any_of(std::begin(kPages), std::end(kPages),
                                       [&](const Page& p) { return path == p.path; });
        if (!(fields >> key >> why) || !known) {
            error = std::string(kPageKeysFile) + ":" + std::to_string(number) +
                    ": not 'PAGE KEY WHY' with a page this check reads: " + line;
            return false;
        }
        own[path].insert(key);
    }
    return true;
}

// The keys the table gives a page: the rows' URL keys and the bases' sizes (by their flags'
// names: radius, length, radii). A page that takes part of the table (the three.js example)
// may also read, by its flag's name, a field the web page does not take (model).
std::set<std::string> tableKeys(bool whole) {
    std::set<std::string> keys;
    for (const SceneField& field : sceneFieldTable()) {
        if (!field.urlKey.empty())
            keys.insert(std::string(field.urlKey));
        else if (!whole && !field.flag.empty())
            keys.insert(std::string(field.flag.substr(2)));
    }
    for (const std::string& size : baseSizeFields()) keys.insert(sceneFieldFlag(size).substr(2));
    return keys;
}

// `page`'s keys against the table's and its own (see Page); the problems found.
std::vector<std::string> checkPage(const Page& page, const std::string& text,
                                   const std::set<std::string>& own) {
    const std::set<std::string> table = tableKeys(page.whole);
    std::set<std::string> readKeys = matches(text, kReadKey);
    std::set<std::string> writtenKeys = matches(text, kWrittenKey);
    if (std::regex_search(text, std::regex(kCoreSizes)))
        for (const std::string& size : baseSizeFields()) {
            const std::string key = sceneFieldFlag(size).substr(2);
            if (text.find(kReadSizes) != std::string::npos) readKeys.insert(key);
            if (text.find(kWrittenSizes) != std::string::npos) writtenKeys.insert(key);
        }
    std::vector<std::string> problems;
    const auto outside = [&](const std::string& key, const char* what) {
        if (!table.count(key) && !own.count(key))
            problems.push_back("it " + std::string(what) + " key " + key +
                               ", which no row of the table of scene fields has (nor " +
                               kPageKeysFile + " as the page's own)");
    };
    for (const std::string& key : readKeys) outside(key, "reads (get)");
    for (const std::string& key : own)
        if (!readKeys.count(key))
            problems.push_back(std::string(kPageKeysFile) + " lists key " + key +
                               " as the page's own, but it never reads it (get)");
    if (readKeys.empty())
        problems.push_back("no get('key' found: the check no longer reads the page");
    if (!page.whole) return problems;
    for (const std::string& key : writtenKeys) outside(key, "writes (q.set)");
    for (const std::string& key : table) {
        if (!readKeys.count(key)) problems.push_back("it never reads (get) key " + key);
        if (!writtenKeys.count(key)) problems.push_back("it never writes (q.set) key " + key);
    }
    for (const std::string& key : own)
        if (!writtenKeys.count(key)) problems.push_back("it never writes (q.set) key " + key);
    if (writtenKeys.empty())
        problems.push_back("no q.set('key' found: the check no longer reads the page");
    return problems;
}

// Each page of kPages under `source` holds the table's URL keys (ctest web.field_keys).
int checkKeys(const std::string& source) {
    std::string ownText;
    if (!read(source + "/" + kPageKeysFile, ownText))
        return fail(source + "/" + kPageKeysFile + ": cannot be read");
    std::map<std::string, std::set<std::string>> ownKeys;
    if (std::string error; !readPageKeys(ownText, ownKeys, error)) return fail(error);
    std::string message;
    for (const Page& page : kPages) {
        const std::string path = source + "/" + page.path;
        std::string text;
        if (!read(path, text)) return fail(path + ": cannot be read");
        const std::set<std::string>& own = ownKeys[page.path];
        const std::vector<std::string> problems = checkPage(page, text, own);
        if (problems.empty()) {
            if (page.whole)
                std::cout << "scene_field_table: " << page.path << " reads and writes the "
                          << tableKeys(true).size() + own.size()
                          << " keys of the table of scene fields and its own\n";
            else
                std::cout << "scene_field_table: " << page.path << " reads "
                          << matches(text, kReadKey).size()
                          << " keys, each the table of scene fields' or its own\n";
            continue;
        }
        message += (message.empty() ? "" : "\n") + path +
                   ": its URL keys are not the table of scene fields' "
                   "(src/core/scene/SceneFields.cpp: a row's urlKey):";
        for (const std::string& problem : problems) message += "\n  " + problem;
    }
    return message.empty() ? 0 : fail(message);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "print" && argc == 2) {
        std::cout << generatedTable();
        return 0;
    }
    if ((mode != "check" && mode != "write" && mode != "keys") || argc != 3)
        return fail(
            "usage: scene_field_table print | check FILE.md | write FILE.md | keys SOURCE_DIR");
    const std::string path = argv[2];
    if (mode == "keys") return checkKeys(path);
    std::string text;
    if (!read(path, text)) return fail(path + ": cannot be read");
    std::size_t begin = 0, end = 0;
    if (!findTable(text, begin, end))
        return fail(path + ": no generated table (a line '" + kBegin + "', then one '" + kEnd +
                    "')");
    const std::string generated = generatedTable();
    const std::string committed = text.substr(begin, end - begin);
    if (mode == "check") {
        if (committed == generated) {
            std::cout << "scene_field_table: " << path << " holds the table of scene fields\n";
            return 0;
        }
        // The first line that differs, so that the failure says what changed.
        std::istringstream a(committed), b(generated);
        std::string lineA, lineB;
        int number = 1;
        while (std::getline(a, lineA) && std::getline(b, lineB) && lineA == lineB) ++number;
        return fail(path +
                    ": its table of scene options is not the one the table of scene "
                    "fields (src/core/scene/SceneFields.cpp) makes; regenerate it: " +
                    kRegenerate + "\n  table line " + std::to_string(number) + " is:\n    " +
                    lineA + "\n  generated:\n    " + lineB);
    }
    text.replace(begin, end - begin, generated);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!(out << text) || !out.flush()) return fail(path + ": cannot be written");
    return 0;
}
