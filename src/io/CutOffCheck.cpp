#include "io/CutOffCheck.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <vector>

namespace microrelief {

namespace {

using Bytes = std::vector<unsigned char>;

// The bytes [offset, offset + size) of the file, or nothing when the file ends before.
std::optional<Bytes> bytesAt(std::ifstream& in, std::uint64_t offset, std::uint64_t size) {
    in.clear();
    in.seekg(static_cast<std::streamoff>(offset));
    Bytes bytes(size);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
    if (!in || static_cast<std::uint64_t>(in.gcount()) != size) return std::nullopt;
    return bytes;
}

std::uint64_t fileSize(std::ifstream& in) {
    in.clear();
    in.seekg(0, std::ios::end);
    const std::streamoff end = in.tellg();
    return end > 0 ? static_cast<std::uint64_t>(end) : 0;
}

bool endsWith(std::ifstream& in, const Bytes& tail) {
    const std::uint64_t size = fileSize(in);
    if (size < tail.size()) return false;
    const std::optional<Bytes> end = bytesAt(in, size - tail.size(), tail.size());
    return end && *end == tail;
}

// An IFF file is one FORM (or FOR4) chunk: its length, big-endian after the tag, covers
// the rest of the file.
bool iffLengthFits(std::ifstream& in) {
    const std::optional<Bytes> head = bytesAt(in, 0, 8);
    if (!head) return false;
    const std::uint64_t length = (std::uint64_t{(*head)[4]} << 24) |
                                 (std::uint64_t{(*head)[5]} << 16) |
                                 (std::uint64_t{(*head)[6]} << 8) | (*head)[7];
    return 8 + length <= fileSize(in);
}

// A TIFF file's directories (TIFF 6.0, section 2): each entry's value, where it does not
// fit the entry's four bytes, at an offset that must lie in the file, and the strips or
// tiles at the offsets and byte counts the directory gives.
class TiffWalk {
public:
    explicit TiffWalk(std::ifstream& in) : in_(in), size_(fileSize(in)) {}

    std::optional<std::string> defect() {
        const std::optional<Bytes> head = bytesAt(in_, 0, 8);
        if (!head) return "the file ends inside the TIFF header";
        little_ = (*head)[0] == 'I';
        if (number(head->data() + 2, 2) == 43) return std::nullopt;  // BigTIFF: the decoder's
        std::uint64_t directory = number(head->data() + 4, 4);
        for (int k = 0; directory != 0; ++k) {
            if (k == 1000) return "TIFF directories in a loop";
            const std::optional<Bytes> count = bytesAt(in_, directory, 2);
            if (!count) return "a TIFF directory lies past the end";
            const std::uint64_t entries = number(count->data(), 2);
            const std::optional<Bytes> table = bytesAt(in_, directory + 2, 12 * entries + 4);
            if (!table) return "a TIFF directory lies past the end";
            if (auto bad = directoryDefect(*table, directory + 2, entries)) return bad;
            directory = number(table->data() + 12 * entries, 4);
        }
        return std::nullopt;
    }

private:
    std::uint64_t number(const unsigned char* p, int bytes) const {
        std::uint64_t value = 0;
        for (int k = 0; k < bytes; ++k)
            value |= std::uint64_t{p[k]} << (8 * (little_ ? k : bytes - 1 - k));
        return value;
    }

    static int typeSize(std::uint64_t type) {
        static constexpr std::array<int, 14> sizes = {0, 1, 1, 2, 4, 8, 1, 1, 2, 4, 8, 4, 8, 4};
        return type < sizes.size() ? sizes[type] : 0;  // 0: a type TIFF 6.0 does not define
    }

    std::optional<std::string> directoryDefect(const Bytes& table, std::uint64_t at,
                                               std::uint64_t entries) {
        std::vector<std::uint64_t> offsets, counts;  // of the strips or tiles
        for (std::uint64_t e = 0; e < entries; ++e) {
            const unsigned char* entry = table.data() + 12 * e;
            const std::uint64_t tag = number(entry, 2), type = number(entry + 2, 2),
                                count = number(entry + 4, 4);
            const int size = typeSize(type);
            const std::uint64_t bytes = count * size;
            if (size == 0) continue;
            const std::uint64_t where = bytes <= 4 ? at + 12 * e + 8 : number(entry + 8, 4);
            if (where + bytes > size_)
                return "the value of TIFF tag " + std::to_string(tag) + " lies past the end";
            const bool location = tag == 273 || tag == 324, length = tag == 279 || tag == 325;
            if (!location && !length) continue;
            const std::optional<Bytes> values = bytesAt(in_, where, bytes);
            if (!values)
                return "the value of TIFF tag " + std::to_string(tag) + " lies past the end";
            std::vector<std::uint64_t>& list = location ? offsets : counts;
            for (std::uint64_t k = 0; k < count; ++k)
                list.push_back(number(values->data() + k * size, size));
        }
        if (offsets.size() != counts.size()) return "TIFF strip offsets and byte counts disagree";
        for (std::size_t k = 0; k < offsets.size(); ++k) {
            if (offsets[k] + counts[k] > size_)
                return "TIFF strip or tile " + std::to_string(k) + " lies past the end";
        }
        return std::nullopt;
    }

    std::ifstream& in_;
    std::uint64_t size_;
    bool little_ = true;
};

}  // namespace

std::optional<std::string> cutOffDefect(const std::filesystem::path& file,
                                        const std::string& format) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return "cannot be read";
    if (format == "jpeg" && !endsWith(in, {0xff, 0xd9})) return "no JPEG end-of-image marker";
    // The TGA 2.0 footer: "TRUEVISION-XFILE." and a null, after two offsets.
    if (format == "targa" && !endsWith(in, {'T', 'R', 'U', 'E', 'V', 'I', 'S', 'I', 'O', 'N', '-',
                                            'X', 'F', 'I', 'L', 'E', '.', 0}))
        return "no TGA footer";
    if (format == "gif" && !endsWith(in, {0x3b})) return "no GIF trailer";
    if (format == "iff" && !iffLengthFits(in)) return "shorter than its FORM chunk says";
    if (format == "tiff") return TiffWalk(in).defect();
    return std::nullopt;
}

}  // namespace microrelief
