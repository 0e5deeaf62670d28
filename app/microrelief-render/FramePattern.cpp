#include "FramePattern.h"

#include <algorithm>
#include <cassert>
#include <charconv>

#include "microrelief/core/Error.h"

namespace microrelief {

FramePattern::FramePattern(const std::string& text, const std::string& flag,
                           const std::vector<std::string>& fields)
    : text_(text) {
    const auto fail = [&](const std::string& reason) {
        throwBadInput(flag + " '" + text + "': " + reason);
    };
    Piece piece;
    for (std::size_t k = 0; k < text.size(); ++k) {
        const char c = text[k];
        if (c == '}') {
            if (k + 1 < text.size() && text[k + 1] == '}') {
                piece.literal += '}';
                ++k;
                continue;
            }
            fail("an unmatched '}' (write '}}' for a brace)");
        }
        if (c != '{') {
            piece.literal += c;
            continue;
        }
        if (k + 1 < text.size() && text[k + 1] == '{') {
            piece.literal += '{';
            ++k;
            continue;
        }
        const std::size_t close = text.find('}', k);
        if (close == std::string::npos) fail("an unmatched '{' (write '{{' for a brace)");
        const std::string inside = text.substr(k + 1, close - k - 1);
        const std::size_t colon = inside.find(':');
        piece.field = inside.substr(0, colon);
        if (std::find(fields.begin(), fields.end(), piece.field) == fields.end()) {
            std::string known;
            for (const std::string& f : fields) known += (known.empty() ? "{" : ", {") + f + "}";
            fail("unknown field {" + piece.field + "} (known: " + known + ")");
        }
        if (colon != std::string::npos) {
            // [0][width]d
            std::string spec = inside.substr(colon + 1);
            if (spec.empty() || spec.back() != 'd')
                fail("{" + inside + "}: the format must be d, Nd or 0Nd, as in {frame:04d}");
            spec.pop_back();
            piece.zeroPad = !spec.empty() && spec.front() == '0';
            if (!spec.empty()) {
                const char* end = spec.data() + spec.size();
                const auto [ptr, ec] = std::from_chars(spec.data(), end, piece.width);
                if (ec != std::errc() || ptr != end || piece.width < 0 || piece.width > 64)
                    fail("{" + inside + "}: the format must be d, Nd or 0Nd, as in {frame:04d}");
            }
        }
        pieces_.push_back(piece);
        piece = {};
        k = close;
    }
    pieces_.push_back(piece);  // the text after the last field
}

bool FramePattern::uses(const std::string& field) const {
    return std::any_of(pieces_.begin(), pieces_.end(),
                       [&](const Piece& p) { return p.field == field; });
}

std::string FramePattern::expand(const std::map<std::string, long long>& values) const {
    std::string name;
    for (const Piece& p : pieces_) {
        name += p.literal;
        if (p.field.empty()) continue;
        const auto found = values.find(p.field);
        assert(found != values.end());
        const long long value = found->second;
        std::string digits = std::to_string(value < 0 ? -value : value);
        const std::size_t sign = value < 0 ? 1 : 0;
        const std::size_t width = static_cast<std::size_t>(p.width);
        if (p.zeroPad && digits.size() + sign < width)
            digits.insert(0, width - sign - digits.size(), '0');
        if (sign) digits.insert(0, 1, '-');
        if (digits.size() < width) digits.insert(0, width - digits.size(), ' ');
        name += digits;
    }
    return name;
}

std::filesystem::path FramePattern::fixedFolder() const {
    // The text up to the first field (all of it without fields), cut back to its last
    // folder separator.
    const std::string& prefix = pieces_.front().literal;
    const std::size_t slash = prefix.rfind('/');
    if (slash == std::string::npos) return {};
    return slash == 0 ? std::filesystem::path("/") : std::filesystem::path(prefix.substr(0, slash));
}

}  // namespace microrelief
