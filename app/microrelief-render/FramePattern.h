// File names from a pattern, one per frame: --out 'out/view-{frame:04d}.png'. Literal
// text with fields in braces, in Python's format syntax cut down to what file names
// need: {name}, {name:d}, {name:Nd} (at least N characters, padded with spaces) and
// {name:0Nd} (padded with zeros); {{ and }} stand for literal braces.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace microrelief {

class FramePattern {
public:
    // `fields` are the names the pattern may use; `flag` names it in messages. Throws
    // Error(BadInput) for an unknown field, a format other than the above or an
    // unmatched brace.
    FramePattern(const std::string& text, const std::string& flag,
                 const std::vector<std::string>& fields = {"frame"});

    const std::string& text() const { return text_; }
    bool uses(const std::string& field) const;

    // The name for these values; `values` must hold every field the pattern uses.
    std::string expand(const std::map<std::string, long long>& values) const;
    std::string expand(const std::string& field, long long value) const {
        return expand(std::map<std::string, long long>{{field, value}});
    }

    // The longest leading folder of the pattern without fields: "out" for both
    // "out/view-{frame}.png" and "out/{frame}/view.png", "" for "view-{frame}.png".
    std::filesystem::path fixedFolder() const;

private:
    struct Piece {
        std::string literal;  // text before the field
        std::string field;    // empty: no field (the last piece)
        int width = 0;
        bool zeroPad = false;
    };
    std::string text_;
    std::vector<Piece> pieces_;
};

}  // namespace microrelief
