#include "io/ExrCheck.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>

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

// The value size OpenEXR 3.1 reads for a type whatever the size field says (a mismatch
// puts its parser out of step with the file: the next "size" it reads is garbage, and it
// allocates that); 0 for the types whose size field it follows or that are checked apart.
std::size_t fixedValueSize(const std::string& type) {
    static const std::map<std::string, std::size_t> sizes = {{"box2i", 16},
                                                             {"box2f", 16},
                                                             {"int", 4},
                                                             {"float", 4},
                                                             {"double", 8},
                                                             {"v2i", 8},
                                                             {"v2f", 8},
                                                             {"v2d", 16},
                                                             {"v3i", 12},
                                                             {"v3f", 12},
                                                             {"v3d", 24},
                                                             {"m33f", 36},
                                                             {"m33d", 72},
                                                             {"m44f", 64},
                                                             {"m44d", 128},
                                                             {"compression", 1},
                                                             {"lineOrder", 1},
                                                             {"envmap", 1},
                                                             {"deepImageState", 1},
                                                             {"chromaticities", 32},
                                                             {"keycode", 28},
                                                             {"timecode", 8},
                                                             {"rational", 8},
                                                             {"tiledesc", 9}};
    const auto found = sizes.find(type);
    return found == sizes.end() ? 0 : found->second;
}

// A channel list as OpenEXR reads it: entries of a name and 16 bytes until an empty
// name, which must be the value's last byte.
bool channelListFits(const std::vector<unsigned char>& value) {
    std::size_t at = 0;
    for (;;) {
        const std::size_t start = at;
        while (at < value.size() && value[at] != 0) ++at;
        if (at == value.size() || at - start > 255) return false;
        ++at;  // the null
        if (at - start == 1) return at == value.size();
        at += 16;
        if (at > value.size()) return false;
    }
}

// A preview image: width, height, then 4 bytes a pixel, which OpenEXR reads in full.
bool previewFits(const std::vector<unsigned char>& value) {
    if (value.size() < 8) return false;
    const std::uint64_t w = static_cast<std::uint32_t>(littleEndian(value.data()));
    const std::uint64_t h = static_cast<std::uint32_t>(littleEndian(value.data() + 4));
    return 8 + 4 * w * h == value.size();
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
            const std::size_t fixed = fixedValueSize(*type);
            if (fixed != 0 && static_cast<std::size_t>(size) != fixed) {
                defect = "attribute '" + printable(*name) + "' of type " + printable(*type) +
                         " has " + std::to_string(size) + " bytes, not " + std::to_string(fixed);
                return std::nullopt;
            }
            if (*type == "chlist" || *type == "preview") {
                std::vector<unsigned char> value(static_cast<std::size_t>(size));
                in.read(reinterpret_cast<char*>(value.data()), size);
                const bool fits = *type == "chlist" ? channelListFits(value) : previewFits(value);
                if (!fits) {
                    defect = "attribute '" + printable(*name) + "' (" + *type +
                             ") does not fill its " + std::to_string(size) + " bytes";
                    return std::nullopt;
                }
            } else if (*name == "dataWindow") {
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
