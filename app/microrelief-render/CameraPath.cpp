#include "CameraPath.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "CommandLine.h"
#include "Csv.h"
#include "microrelief/core/Error.h"

namespace microrelief {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A camera's error, with `where` in front ("cams.csv: line 4 (frame 2): ").
void checkCamera(const Camera& camera, const std::string& where) {
    if (camera.eye == camera.target)
        throwBadInput(where + "the eye and the target are the same point");
    if (!(camera.fovyDegrees > 0.0 && camera.fovyDegrees < 180.0))
        throwBadInput(where + "fovy must lie strictly between 0 and 180 degrees");
    // The positions' range first, as --eye and --target have it (core/scene/Scene.h,
    // checkPoint): a turntable's turned eye or a row's columns may leave it, and an eye of
    // 1e300 would otherwise be called the target's point.
    std::vector<FieldError> errors;
    checkPoint(errors, "camera.eye", camera.eye);
    checkPoint(errors, "camera.target", camera.target);
    try {
        throwIfInvalid(errors);
        resolveCamera(camera, 1, 1, 1.0);  // the rules a picture is drawn by
    } catch (const Error& e) {
        throw e.after(where);
    }
}

glm::dvec3 turnAboutY(const glm::dvec3& v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    // + 0.0 turns a -0 into 0, which reads better in the manifest.
    return {c * v.x + s * v.z + 0.0, v.y, -s * v.x + c * v.z + 0.0};
}

// One number of a row: the whole text, finite. `what` names the column or key.
double parseNumber(std::string text, const std::string& what, const std::string& where) {
    if (text.empty()) throwBadInput(where + what + " is empty");
    const std::string given = text;
    if (text.front() == '+') text.erase(0, 1);
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ptr != end || (ec != std::errc() && ec != std::errc::result_out_of_range))
        throwBadInput(where + what + ": '" + given + "' is not a number");
    if (!std::isfinite(value) || ec == std::errc::result_out_of_range)
        throwBadInput(where + what + ": '" + given + "' is not a finite number");
    return value;
}

// What a row gives; the rest comes from the command line.
struct RowCamera {
    std::optional<glm::dvec3> eye, target, up;
    std::optional<double> fovy;
    std::string flags;
};

// What a row's flags are, with two of them as examples.
std::string rowFlagsAre() {
    return "a row's flags are map and shading flags, such as " + flagName("map.file") + " or " +
           flagName("shading.lightDirection");
}

// The row's flags on top of the command line's scene: the flags' parser (SceneFlags)
// seeded with the scene's fields, so that a row's flag sets its field and every other
// field keeps the scene's value.
SceneOptions applyRowFlags(const SceneOptions& base, const std::string& flags,
                           const std::string& where) {
    SceneOptions row = base;
    CLI::App app;
    SceneFlags scene(row);
    scene.addMapAndCamera(app);
    scene.addShading(app);
    try {
        app.parse(flags, false);
    } catch (const CLI::CallForHelp&) {
        // CLI11 would say "This should be caught in your main function".
        throwBadInput(where + "flags: --help is not a row flag (" + rowFlagsAre() + ")");
    } catch (const CLI::ExtrasError& e) {
        throwBadInput(where + "flags: " + parseErrorText(e, app) + "; " + rowFlagsAre() +
                      " (--out, --memory and the like are the command line's)");
    } catch (const CLI::ParseError& e) {
        throwBadInput(where + "flags: " + parseErrorText(e, app));
    }
    refuseEmptyValues(app, where + "flags: ");
    for (const char* field : {"camera.eye", "camera.target", "camera.up", "camera.fovyDegrees"}) {
        if (app.count(flagName(field)) > 0)
            throwBadInput(where + "flags: " + flagName(field) +
                          " is not a row flag (the camera comes from the columns)");
    }
    try {
        scene.apply();
    } catch (const Error& e) {
        throw e.after(where + "flags: ");
    }
    return row;
}

PathFrame makeFrame(const RowCamera& row, const SceneOptions& base, const std::string& origin) {
    const std::string where = origin + ": ";
    PathFrame frame;
    frame.scene = row.flags.empty() ? base : applyRowFlags(base, row.flags, where);
    frame.flags = row.flags;
    frame.origin = origin;
    Camera& camera = frame.scene.job.camera;
    camera.eye = *row.eye;
    camera.target = *row.target;
    camera.up = row.up.value_or(base.job.camera.up);
    camera.fovyDegrees = row.fovy.value_or(base.job.camera.fovyDegrees);
    checkCamera(camera, where);
    return frame;
}

std::string rowOrigin(const std::string& source, int line, int frame) {
    return source + ": line " + std::to_string(line) + " (frame " + std::to_string(frame) + ")";
}

// ---- CSV ----

const char* const kVectorColumns[3][3] = {
    {"eye_x", "eye_y", "eye_z"}, {"target_x", "target_y", "target_z"}, {"up_x", "up_y", "up_z"}};

struct CsvLayout {
    std::map<std::string, std::size_t> columns;  // name -> position
    std::size_t width = 0;
};

CsvLayout parseHeader(const std::string& text, const std::string& where) {
    const auto fields = splitCsvLine(text);
    if (!fields) throwBadInput(where + "an unclosed quote in the header");
    std::vector<std::string> known;
    for (const auto& vector : kVectorColumns)
        for (const char* name : vector) known.push_back(name);
    known.push_back("fovy");
    known.push_back("flags");
    std::string knownText;
    for (const std::string& k : known) knownText += (knownText.empty() ? "" : ", ") + k;

    CsvLayout layout;
    layout.width = fields->size();
    for (std::size_t k = 0; k < fields->size(); ++k) {
        const std::string& name = (*fields)[k];
        double ignored = 0.0;
        const bool number =
            !name.empty() &&
            std::from_chars(name.data(), name.data() + name.size(), ignored).ec == std::errc();
        if (number)
            throwBadInput(where + "the first line must name the columns (" + knownText +
                          "), not '" + name + "'");
        if (std::find(known.begin(), known.end(), name) == known.end())
            throwBadInput(where + "unknown column '" + name + "' (the columns are " + knownText +
                          ")");
        if (!layout.columns.emplace(name, k).second)
            throwBadInput(where + "the column " + name + " appears twice");
    }
    for (int v = 0; v < 3; ++v) {
        int present = 0;
        for (const char* name : kVectorColumns[v]) present += layout.columns.count(name) > 0;
        if (present == 3 || (v == 2 && present == 0)) continue;
        for (const char* name : kVectorColumns[v]) {
            if (layout.columns.count(name) == 0)
                throwBadInput(where + "no column " + name +
                              (v == 2 ? " (up needs up_x, up_y and up_z)"
                                      : " (needed: eye_x, eye_y, eye_z, target_x, target_y, "
                                        "target_z)"));
        }
    }
    return layout;
}

RowCamera parseCsvRow(const std::string& text, const CsvLayout& layout, const std::string& where) {
    const auto fields = splitCsvLine(text);
    if (!fields) throwBadInput(where + "an unclosed quote, or text after a closing quote");
    if (fields->size() != layout.width)
        throwBadInput(where + std::to_string(fields->size()) + " fields, but the header names " +
                      std::to_string(layout.width) + " columns");
    const auto field = [&](const std::string& name) -> const std::string* {
        const auto found = layout.columns.find(name);
        return found == layout.columns.end() ? nullptr : &(*fields)[found->second];
    };
    RowCamera row;
    const auto vector = [&](int v) -> std::optional<glm::dvec3> {
        const std::string* x = field(kVectorColumns[v][0]);
        if (!x) return std::nullopt;  // an optional vector without columns
        const std::string* y = field(kVectorColumns[v][1]);
        const std::string* z = field(kVectorColumns[v][2]);
        if (v == 2 && x->empty() && y->empty() && z->empty()) return std::nullopt;
        return glm::dvec3(parseNumber(*x, kVectorColumns[v][0], where),
                          parseNumber(*y, kVectorColumns[v][1], where),
                          parseNumber(*z, kVectorColumns[v][2], where));
    };
    row.eye = vector(0);
    row.target = vector(1);
    row.up = vector(2);
    if (const std::string* fovy = field("fovy"); fovy && !fovy->empty())
        row.fovy = parseNumber(*fovy, "fovy", where);
    if (const std::string* flags = field("flags")) row.flags = *flags;
    return row;
}

// ---- JSON lines ----

// A JSON value, as far as camera rows need: numbers keep their text (so that NaN or a
// typo gets the same message as in CSV), objects their members in order.
// (A member is a struct of its own, not a std::pair: a pair of an incomplete JsonValue
// does not compile with clang and libstdc++ 12, the sanitizer build's.)
struct JsonMember;
struct JsonValue {
    enum class Kind { Null, Boolean, Number, String, Array, Object } kind = Kind::Null;
    std::string text;  // a number's token, a string's contents
    std::vector<JsonValue> items;
    std::vector<JsonMember> members;
};
struct JsonMember {
    std::string key;
    JsonValue value;
};

class JsonReader {
public:
    explicit JsonReader(const std::string& text) : s_(text) {}

    // The whole text as one value; throws a reason and a column as std::string.
    JsonValue document() {
        JsonValue v = value(0);
        space();
        if (p_ != s_.size()) fail("text after the object");
        return v;
    }

private:
    [[noreturn]] void fail(const std::string& reason) {
        throw reason + " at column " + std::to_string(p_ + 1);
    }
    void space() {
        while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t')) ++p_;
    }
    bool take(char c) {
        space();
        if (p_ < s_.size() && s_[p_] == c) {
            ++p_;
            return true;
        }
        return false;
    }
    void expect(char c) {
        if (!take(c)) fail(std::string("expected '") + c + "'");
    }

    JsonValue value(int depth) {
        if (depth > 16) fail("nested too deeply");
        space();
        if (p_ >= s_.size()) fail("a value is missing");
        JsonValue v;
        const char c = s_[p_];
        if (c == '{') {
            ++p_;
            v.kind = JsonValue::Kind::Object;
            if (take('}')) return v;
            do {
                space();
                if (p_ >= s_.size() || s_[p_] != '"') fail("expected a key in quotes");
                std::string key = string();
                expect(':');
                v.members.push_back({std::move(key), value(depth + 1)});
            } while (take(','));
            expect('}');
        } else if (c == '[') {
            ++p_;
            v.kind = JsonValue::Kind::Array;
            if (take(']')) return v;
            do v.items.push_back(value(depth + 1));
            while (take(','));
            expect(']');
        } else if (c == '"') {
            v.kind = JsonValue::Kind::String;
            v.text = string();
        } else {
            // A bare token: a number, true, false, null, or something else (NaN, abc)
            // that the caller names as "not a number".
            const std::size_t start = p_;
            while (p_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[p_])) ||
                                      s_[p_] == '.' || s_[p_] == '-' || s_[p_] == '+'))
                ++p_;
            if (p_ == start) fail(std::string("unexpected '") + c + "'");
            v.text = s_.substr(start, p_ - start);
            v.kind = v.text == "null"                        ? JsonValue::Kind::Null
                     : v.text == "true" || v.text == "false" ? JsonValue::Kind::Boolean
                                                             : JsonValue::Kind::Number;
        }
        return v;
    }

    std::string string() {
        ++p_;  // the opening quote
        std::string out;
        while (true) {
            if (p_ >= s_.size()) fail("a string is not closed");
            const char c = s_[p_++];
            if (c == '"') return out;
            if (c != '\\') {
                out += c;
                continue;
            }
            if (p_ >= s_.size()) fail("a string is not closed");
            const char e = s_[p_++];
            switch (e) {
                case '"':
                    out += '"';
                    break;
                case '\\':
                    out += '\\';
                    break;
                case '/':
                    out += '/';
                    break;
                case 'b':
                    out += '\b';
                    break;
                case 'f':
                    out += '\f';
                    break;
                case 'n':
                    out += '\n';
                    break;
                case 'r':
                    out += '\r';
                    break;
                case 't':
                    out += '\t';
                    break;
                case 'u':
                    unicode(out);
                    break;
                default:
                    fail(std::string("unknown escape \\") + e);
            }
        }
    }

    unsigned hex4() {
        if (p_ + 4 > s_.size()) fail("a \\u escape needs four hex digits");
        unsigned value = 0;
        const auto [ptr, ec] = std::from_chars(s_.data() + p_, s_.data() + p_ + 4, value, 16);
        if (ec != std::errc() || ptr != s_.data() + p_ + 4)
            fail("a \\u escape needs four hex digits");
        p_ += 4;
        return value;
    }

    void unicode(std::string& out) {
        unsigned code = hex4();
        if (code >= 0xD800 && code < 0xDC00 && s_.compare(p_, 2, "\\u") == 0) {
            p_ += 2;
            const unsigned low = hex4();
            if (low < 0xDC00 || low >= 0xE000) fail("a lone surrogate in a \\u escape");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
        }
        if (code < 0x80) {
            out += static_cast<char>(code);
        } else if (code < 0x800) {
            out += static_cast<char>(0xC0 | code >> 6);
            out += static_cast<char>(0x80 | (code & 0x3F));
        } else if (code < 0x10000) {
            out += static_cast<char>(0xE0 | code >> 12);
            out += static_cast<char>(0x80 | (code >> 6 & 0x3F));
            out += static_cast<char>(0x80 | (code & 0x3F));
        } else {
            out += static_cast<char>(0xF0 | code >> 18);
            out += static_cast<char>(0x80 | (code >> 12 & 0x3F));
            out += static_cast<char>(0x80 | (code >> 6 & 0x3F));
            out += static_cast<char>(0x80 | (code & 0x3F));
        }
    }

    const std::string& s_;
    std::size_t p_ = 0;
};

RowCamera parseJsonRow(const std::string& text, const std::string& where) {
    JsonValue object;
    try {
        object = JsonReader(text).document();
    } catch (const std::string& reason) {
        throwBadInput(where + "not a JSON object (" + reason + ")");
    }
    if (object.kind != JsonValue::Kind::Object) throwBadInput(where + "not a JSON object");
    RowCamera row;
    std::map<std::string, const JsonValue*> seen;
    for (const auto& [key, value] : object.members) {
        if (!seen.emplace(key, &value).second)
            throwBadInput(where + "the key \"" + key + "\" appears twice");
    }
    const auto vector = [&](const char* key) -> std::optional<glm::dvec3> {
        const auto found = seen.find(key);
        if (found == seen.end() || found->second->kind == JsonValue::Kind::Null)
            return std::nullopt;
        const JsonValue& v = *found->second;
        if (v.kind != JsonValue::Kind::Array || v.items.size() != 3)
            throwBadInput(where + key + " must be an array of three numbers [x, y, z]");
        glm::dvec3 result;
        for (int k = 0; k < 3; ++k) {
            const std::string what = std::string(key) + "[" + std::to_string(k) + "]";
            if (v.items[k].kind != JsonValue::Kind::Number)
                throwBadInput(where + what + " is not a number");
            result[k] = parseNumber(v.items[k].text, what, where);
        }
        return result;
    };
    for (const auto& [key, value] : seen) {
        if (key != "eye" && key != "target" && key != "up" && key != "fovy" && key != "flags")
            throwBadInput(where + "unknown key \"" + key +
                          "\" (the keys are eye, target, up, fovy, flags)");
    }
    row.eye = vector("eye");
    row.target = vector("target");
    row.up = vector("up");
    if (!row.eye)
        throwBadInput(where + "no \"eye\" (needed: \"eye\": [x, y, z], \"target\": [x, y, z])");
    if (!row.target)
        throwBadInput(where + "no \"target\" (needed: \"eye\": [x, y, z], \"target\": [x, y, z])");
    if (const auto fovy = seen.find("fovy");
        fovy != seen.end() && fovy->second->kind != JsonValue::Kind::Null) {
        if (fovy->second->kind != JsonValue::Kind::Number)
            throwBadInput(where + "fovy is not a number");
        row.fovy = parseNumber(fovy->second->text, "fovy", where);
    }
    if (const auto flags = seen.find("flags");
        flags != seen.end() && flags->second->kind != JsonValue::Kind::Null) {
        if (flags->second->kind != JsonValue::Kind::String)
            throwBadInput(where + "flags must be a string of command-line flags");
        row.flags = flags->second->text;
    }
    return row;
}

bool skipped(const std::string& line) {
    const std::size_t first = line.find_first_not_of(" \t");
    return first == std::string::npos || line[first] == '#';
}

}  // namespace

std::string cameraFlags(const Camera& camera) {
    // The flags by field (core/scene/SceneFields.h); "=" keeps a leading minus a value.
    return flagName("camera.eye") + "=" + exactVector(camera.eye) + " " +
           flagName("camera.target") + "=" + exactVector(camera.target) + " " +
           flagName("camera.up") + "=" + exactVector(camera.up) + " " +
           flagName("camera.fovyDegrees") + " " + exactNumber(camera.fovyDegrees);
}

PathFrame turntableFrame(const SceneOptions& base, int views, int k) {
    PathFrame frame;
    frame.scene = base;
    frame.origin = "--turntable frame " + std::to_string(k);
    Camera& camera = frame.scene.job.camera;
    if (k > 0) {
        const double angle = 2.0 * kPi * k / views;
        camera.eye = camera.target + turnAboutY(camera.eye - camera.target, angle);
        camera.up = turnAboutY(camera.up, angle);
    }
    // Frame 0 is the command line's camera, whose flags name the problem.
    if (k == 0) {
        resolveCamera(camera, 1, 1, 1.0);
    } else {
        checkCamera(camera, frame.origin + ": ");
    }
    return frame;
}

std::vector<PathFrame> turntablePath(const SceneOptions& base, int views) {
    if (views < 1) throwBadInput("--turntable needs at least 1 view");
    std::vector<PathFrame> path;
    path.reserve(static_cast<std::size_t>(views));
    for (int k = 0; k < views; ++k) path.push_back(turntableFrame(base, views, k));
    return path;
}

CameraPath CameraPath::turntable(const SceneOptions& base, int views) {
    if (views < 1) throwBadInput("--turntable needs at least 1 view");
    turntableFrame(base, views, 0);  // the command line's camera: refused now, not later
    CameraPath path;
    path.base_ = base;
    path.views_ = views;
    return path;
}

PathFrame CameraPath::frame(int k) const {
    return base_ ? turntableFrame(*base_, views_, k) : rows_.at(static_cast<std::size_t>(k));
}

bool CameraPath::anySoftShadows() const {
    if (base_) return base_->job.shading.shadows == ShadowMode::Soft;
    return std::any_of(rows_.begin(), rows_.end(), [](const PathFrame& f) {
        return f.scene.job.shading.shadows == ShadowMode::Soft;
    });
}

std::vector<PathFrame> parseCameraFile(const std::string& text, const std::string& source,
                                       const SceneOptions& base) {
    std::vector<PathFrame> path;
    // A byte order mark (spreadsheets save "CSV UTF-8" with one) is no part of the header.
    const std::string_view bom = "\xEF\xBB\xBF";
    std::istringstream in(text.compare(0, bom.size(), bom) == 0 ? text.substr(bom.size()) : text);
    std::string line;
    int lineNumber = 0;
    std::optional<CsvLayout> csv;
    bool json = false, first = true;
    while (std::getline(in, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (skipped(line)) continue;
        if (first) {
            first = false;
            json = line[line.find_first_not_of(" \t")] == '{';
            if (!json) {
                csv = parseHeader(line, source + ": line " + std::to_string(lineNumber) + ": ");
                continue;
            }
        }
        const int frame = static_cast<int>(path.size());
        const std::string origin = rowOrigin(source, lineNumber, frame);
        const RowCamera row =
            json ? parseJsonRow(line, origin + ": ") : parseCsvRow(line, *csv, origin + ": ");
        path.push_back(makeFrame(row, base, origin));
    }
    if (path.empty()) throwBadInput(source + ": no cameras (a header, then one camera a line)");
    return path;
}

std::vector<PathFrame> readCameraFile(const std::filesystem::path& file, const SceneOptions& base) {
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (!std::filesystem::exists(status)) throwBadInput(file.string() + ": no such file");
    if (!std::filesystem::is_regular_file(status))
        throwBadInput(file.string() + ": not a regular file");
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in && !in.eof()) throwBadInput(file.string() + ": cannot read");
    return parseCameraFile(text.str(), file.string(), base);
}

}  // namespace microrelief
