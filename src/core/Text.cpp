#include "microrelief/core/Text.h"

#include <cstdint>
#include <sstream>

namespace microrelief {

namespace {

// The length of the well-formed UTF-8 sequence at `s[k]` (RFC 3629: no overlong forms, no
// surrogates, nothing beyond U+10FFFF), or 0 when there is none.
std::size_t utf8Length(std::string_view s, std::size_t k) {
    const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(s[i]); };
    const std::uint8_t b = byte(k);
    std::size_t n = 0;
    std::uint8_t low = 0x80, high = 0xBF;  // the allowed range of the second byte
    if (b >= 0xC2 && b <= 0xDF) {
        n = 2;
    } else if (b >= 0xE0 && b <= 0xEF) {
        n = 3;
        if (b == 0xE0) low = 0xA0;
        if (b == 0xED) high = 0x9F;
    } else if (b >= 0xF0 && b <= 0xF4) {
        n = 4;
        if (b == 0xF0) low = 0x90;
        if (b == 0xF4) high = 0x8F;
    } else {
        return 0;
    }
    if (k + n > s.size() || byte(k + 1) < low || byte(k + 1) > high) return 0;
    for (std::size_t i = 2; i < n; ++i) {
        if (byte(k + i) < 0x80 || byte(k + i) > 0xBF) return 0;
    }
    return n;
}

}  // namespace

std::string printable(std::string_view text) {
    static const char* const kHex = "0123456789ABCDEF";
    std::string out;
    out.reserve(text.size());
    for (std::size_t k = 0; k < text.size();) {
        const auto c = static_cast<std::uint8_t>(text[k]);
        if (c >= 0x20 && c < 0x7F) {
            out += static_cast<char>(c);
            ++k;
        } else if (c == '\r' || c == '\n' || c == '\t') {
            out += c == '\r' ? "\\r" : c == '\n' ? "\\n" : "\\t";
            ++k;
        } else if (const std::size_t n = c >= 0x80 ? utf8Length(text, k) : 0; n > 0) {
            out.append(text.substr(k, n));
            k += n;
        } else {
            out += "\\x";
            out += kHex[c >> 4];
            out += kHex[c & 0xF];
            ++k;
        }
    }
    return out;
}

std::string formatNumber(double value, int significant) {
    std::ostringstream text;
    text.precision(significant);
    text << value;
    return text.str();
}

std::string joinWords(const std::vector<std::string>& words, std::string_view last) {
    std::string text;
    for (std::size_t k = 0; k < words.size(); ++k) {
        if (k > 0) text += k + 1 == words.size() ? std::string(last) : std::string(", ");
        text += words[k];
    }
    return text;
}

}  // namespace microrelief
