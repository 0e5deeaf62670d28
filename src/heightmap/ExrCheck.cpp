#include "heightmap/ExrCheck.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace microrelief {

namespace {

constexpr std::array<unsigned char, 4> kMagic = {0x76, 0x2f, 0x31, 0x01};
constexpr std::uint32_t kLongNames = 0x400, kMultipart = 0x1000;

std::int32_t littleEndian(const unsigned char* p) {
    return static_cast<std::int32_t>(std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) |
                                     (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24));
}

// A null-terminated string of at most `maxLength` characters; empty optional when the
// file ends first or the string is longer.
std::optional<std::string> readName(std::ifstream& in, std::size_t maxLength) {
    std::string name;
    for (;;) {
        const int c = in.get();
        if (c == std::char_traits<char>::eof()) return std::nullopt;
        if (c == 0) return name;
        if (name.size() == maxLength) return std::nullopt;
        name += static_cast<char>(c);
    }
}

// An attribute name for a message: printable, one line.
std::string printable(const std::string& name) {
    std::string text = name;
    for (char& c : text) {
        if (c < 0x20 || c > 0x7e) c = '?';
    }
    return text;
}

}  // namespace

bool hasExrMagic(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 4> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    return in.gcount() == 4 && head == kMagic;
}

std::optional<std::vector<ExrPartSize>> readExrHeader(const std::filesystem::path& file,
                                                      std::string& defect) {
    std::error_code ec;
    const std::uintmax_t fileSize = std::filesystem::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    unsigned char head[8];
    in.read(reinterpret_cast<char*>(head), 8);
    if (ec || in.gcount() != 8) {
        defect = "the file ends inside the OpenEXR header";
        return std::nullopt;
    }
    const std::uint32_t version = static_cast<std::uint32_t>(littleEndian(head + 4));
    const std::size_t maxName = (version & kLongNames) ? 255 : 31;
    const bool multipart = (version & kMultipart) != 0;

    std::vector<ExrPartSize> parts;
    for (;;) {  // one header per part; a multi-part file ends the list with an empty one
        std::optional<ExrPartSize> window;
        bool first = true;
        for (;;) {  // attributes: name, type, size, value; an empty name ends the header
            const std::optional<std::string> name = readName(in, maxName);
            if (!name) {
                defect = "an attribute name runs past the end of the file or is too long";
                return std::nullopt;
            }
            if (name->empty()) break;
            first = false;
            const std::optional<std::string> type = readName(in, maxName);
            unsigned char sizeBytes[4];
            in.read(reinterpret_cast<char*>(sizeBytes), 4);
            if (!type || in.gcount() != 4) {
                defect = "attribute '" + printable(*name) + "' runs past the end of the file";
                return std::nullopt;
            }
            const std::int32_t size = littleEndian(sizeBytes);
            const std::uintmax_t at = static_cast<std::uintmax_t>(in.tellg());
            if (size < 0 || at + static_cast<std::uintmax_t>(size) > fileSize) {
                defect = "attribute '" + printable(*name) + "' claims " + std::to_string(size) +
                         " bytes, more than the file holds";
                return std::nullopt;
            }
            if (*name == "dataWindow") {
                if (*type != "box2i" || size != 16) {
                    defect = "the data window is not a box2i";
                    return std::nullopt;
                }
                unsigned char box[16];
                in.read(reinterpret_cast<char*>(box), 16);
                const long long xMin = littleEndian(box), yMin = littleEndian(box + 4);
                const long long xMax = littleEndian(box + 8), yMax = littleEndian(box + 12);
                window = ExrPartSize{xMax - xMin + 1, yMax - yMin + 1};
            } else {
                in.seekg(size, std::ios::cur);
            }
        }
        if (first && multipart && !parts.empty()) break;  // the empty header: the end
        if (!window) {
            defect = "a header without a data window";
            return std::nullopt;
        }
        parts.push_back(*window);
        if (!multipart) break;
    }
    return parts;
}

}  // namespace microrelief
