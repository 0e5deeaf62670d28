#include "io/PngCheck.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <vector>

namespace microrelief {

namespace {

constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::uint32_t kMaxChunkLength = 0x7fffffffu;  // PNG's "31-bit" integers

std::uint32_t bigEndian(const unsigned char* p) {
    return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
           std::uint32_t{p[3]};
}

std::string chunkName(std::uint32_t type) {
    std::string name(4, ' ');
    for (int k = 0; k < 4; ++k) {
        const char c = static_cast<char>((type >> (24 - 8 * k)) & 0xff);
        name[k] = (c >= 0x20 && c < 0x7f) ? c : '?';
    }
    return name;
}

constexpr std::uint32_t tag(const char (&name)[5]) {
    return (std::uint32_t(static_cast<unsigned char>(name[0])) << 24) |
           (std::uint32_t(static_cast<unsigned char>(name[1])) << 16) |
           (std::uint32_t(static_cast<unsigned char>(name[2])) << 8) |
           std::uint32_t(static_cast<unsigned char>(name[3]));
}

bool isLetter(unsigned c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

// Channels of a colour type, 0 for an invalid one; the bit depths it allows.
int channelsOf(int colorType) {
    switch (colorType) {
        case 0:
            return 1;  // grey
        case 2:
            return 3;  // RGB
        case 3:
            return 1;  // palette index
        case 4:
            return 2;  // grey, alpha
        case 6:
            return 4;  // RGBA
        default:
            return 0;
    }
}

bool validDepth(int colorType, int depth) {
    switch (colorType) {
        case 0:
            return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
        case 3:
            return depth == 1 || depth == 2 || depth == 4 || depth == 8;
        default:
            return depth == 8 || depth == 16;
    }
}

// libpng's png_check_IHDR, the parts that are errors (not warnings).
std::optional<std::string> headerDefect(const unsigned char* data) {
    const std::uint32_t width = bigEndian(data), height = bigEndian(data + 4);
    const int depth = data[8], colorType = data[9];
    if (width == 0 || height == 0) return "IHDR gives a zero size";
    if (width > kMaxChunkLength || height > kMaxChunkLength) return "IHDR size out of range";
    if (channelsOf(colorType) == 0) return "IHDR colour type " + std::to_string(colorType);
    if (!validDepth(colorType, depth))
        return "IHDR bit depth " + std::to_string(depth) + " for colour type " +
               std::to_string(colorType);
    if (data[10] != 0) return "IHDR compression method " + std::to_string(data[10]);
    if (data[11] != 0) return "IHDR filter method " + std::to_string(data[11]);
    if (data[12] > 1) return "IHDR interlace method " + std::to_string(data[12]);
    return std::nullopt;
}

PngHeader headerOf(const unsigned char* data) {
    return {bigEndian(data), bigEndian(data + 4), data[8], data[9], data[12] == 1};
}

// The rows libpng inflates: one per row of each Adam7 pass that has pixels (or of the
// picture), each a filter byte and the row's packed bytes.
struct Rows {
    std::vector<std::uint64_t> bytes;  // per row, filter byte included
};

Rows rowsOf(const PngHeader& h) {
    const std::uint64_t bitsPerPixel = std::uint64_t(channelsOf(h.colorType)) * h.bitDepth;
    auto rowBytes = [&](std::uint64_t width) { return 1 + (width * bitsPerPixel + 7) / 8; };
    Rows rows;
    if (!h.interlaced) {
        rows.bytes.assign(h.height, rowBytes(h.width));
        return rows;
    }
    // Adam7 passes: first column and row, and their steps.
    const int x0[7] = {0, 4, 0, 2, 0, 1, 0}, dx[7] = {8, 8, 4, 4, 2, 2, 1};
    const int y0[7] = {0, 0, 4, 0, 2, 0, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
    for (int pass = 0; pass < 7; ++pass) {
        const std::uint64_t w =
            h.width > std::uint32_t(x0[pass]) ? (h.width - x0[pass] + dx[pass] - 1) / dx[pass] : 0;
        const std::uint64_t n = h.height > std::uint32_t(y0[pass])
                                    ? (h.height - y0[pass] + dy[pass] - 1) / dy[pass]
                                    : 0;
        if (w == 0) continue;
        rows.bytes.insert(rows.bytes.end(), n, rowBytes(w));
    }
    return rows;
}

// Inflates the image data as it arrives and checks each row's filter type, stopping at
// the size IHDR implies (libpng reads no further; what follows only warns).
class ImageDataCheck {
public:
    explicit ImageDataCheck(const PngHeader& header) : rows_(rowsOf(header)) {
        ok_ = inflateInit(&stream_) == Z_OK;
        if (!ok_) defect_ = "cannot start zlib";
        skipEmptyRows();
    }
    ~ImageDataCheck() { inflateEnd(&stream_); }
    ImageDataCheck(const ImageDataCheck&) = delete;
    ImageDataCheck& operator=(const ImageDataCheck&) = delete;

    bool complete() const { return row_ == rows_.bytes.size(); }
    const std::optional<std::string>& defect() const { return defect_; }

    void feed(const unsigned char* data, std::size_t size) {
        if (!ok_ || complete()) return;
        stream_.next_in = const_cast<unsigned char*>(data);
        stream_.avail_in = static_cast<uInt>(size);
        while (stream_.avail_in > 0 && !complete()) {
            // Never inflate past the end of the image data: stop at the current row's end.
            const std::uint64_t wanted =
                std::min<std::uint64_t>(buffer_.size(), rows_.bytes[row_] - inRow_);
            stream_.next_out = buffer_.data();
            stream_.avail_out = static_cast<uInt>(wanted);
            const int status = inflate(&stream_, Z_NO_FLUSH);
            const std::size_t produced = wanted - stream_.avail_out;
            consume(produced);
            if (!ok_) return;
            if (status == Z_STREAM_END) {
                if (!complete()) fail("IDAT: not enough image data");
                ok_ = false;
                return;
            }
            if (status != Z_OK && status != Z_BUF_ERROR) {
                fail(std::string("IDAT: ") + (stream_.msg ? stream_.msg : "zlib error"));
                return;
            }
            if (produced == 0 && stream_.avail_in > 0 && status == Z_BUF_ERROR) {
                fail("IDAT: zlib made no progress");
                return;
            }
        }
    }

private:
    void consume(std::size_t produced) {
        std::size_t at = 0;
        while (at < produced && ok_) {
            if (inRow_ == 0 && buffer_[at] > 4) {
                fail("IDAT: bad filter type " + std::to_string(buffer_[at]));
                return;
            }
            const std::uint64_t take =
                std::min<std::uint64_t>(produced - at, rows_.bytes[row_] - inRow_);
            at += take;
            inRow_ += take;
            if (inRow_ == rows_.bytes[row_]) {
                ++row_;
                inRow_ = 0;
                skipEmptyRows();
            }
        }
    }
    void skipEmptyRows() {
        while (row_ < rows_.bytes.size() && rows_.bytes[row_] == 0) ++row_;
    }
    void fail(const std::string& why) {
        defect_ = why;
        ok_ = false;
    }

    Rows rows_;
    std::size_t row_ = 0;
    std::uint64_t inRow_ = 0;
    z_stream stream_{};
    std::array<unsigned char, 1 << 16> buffer_{};
    bool ok_ = false;
    std::optional<std::string> defect_;
};

}  // namespace

bool hasPngSignature(const std::filesystem::path& file) {
    // The first four bytes, as libpng itself decides: past them a damaged signature is
    // its error ("corrupted by ASCII conversion"), and pngStructureDefect's too.
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 4> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    return in.gcount() == 4 && std::equal(head.begin(), head.end(), kSignature.begin());
}

std::optional<PngHeader> readPngHeader(const std::filesystem::path& file, std::string& defect) {
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 8 + 8 + 13> head{};
    in.read(reinterpret_cast<char*>(head.data()), head.size());
    if (in.gcount() != static_cast<std::streamsize>(head.size())) {
        defect = "the file ends inside the PNG header";
        return std::nullopt;
    }
    if (!std::equal(kSignature.begin(), kSignature.end(), head.begin())) {
        defect = "a damaged PNG signature";
        return std::nullopt;
    }
    if (bigEndian(&head[8]) != 13 || bigEndian(&head[12]) != tag("IHDR")) {
        defect = "the first chunk is not a 13-byte IHDR";
        return std::nullopt;
    }
    if (auto bad = headerDefect(&head[16])) {
        defect = *bad;
        return std::nullopt;
    }
    return headerOf(&head[16]);
}

std::optional<std::string> pngStructureDefect(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::array<unsigned char, 8> signature{};
    in.read(reinterpret_cast<char*>(signature.data()), signature.size());
    if (in.gcount() != 8 || signature != kSignature) return "not a PNG signature";

    std::optional<PngHeader> header;
    std::optional<ImageDataCheck> image;
    bool havePalette = false, inImageData = false, imageDataDone = false;
    std::vector<unsigned char> data;
    std::vector<unsigned char> piece(1 << 16);
    for (;;) {
        unsigned char head[8];
        in.read(reinterpret_cast<char*>(head), 8);
        if (in.gcount() != 8) return "the file ends before IEND (truncated)";
        const std::uint32_t length = bigEndian(head), type = bigEndian(head + 4);
        const std::string name = chunkName(type);
        if (length > kMaxChunkLength) return name + ": chunk length out of range";
        for (int k = 0; k < 4; ++k) {
            if (!isLetter(head[4 + k])) return "invalid chunk type '" + name + "'";
        }
        const bool critical = (head[4] & 0x20) == 0;
        if (!header && type != tag("IHDR")) return name + " before IHDR";

        // Where the image data starts and ends: libpng inflates the IDAT chunks that
        // follow each other, and wants the whole image from them.
        if (type == tag("IDAT")) {
            if (imageDataDone && !image->complete()) return "IDAT: not enough image data";
            if (!inImageData && !imageDataDone) {
                if (header->colorType == 3 && !havePalette) return "a palette image without PLTE";
                image.emplace(*header);
                inImageData = true;
            }
        } else if (inImageData) {
            inImageData = false;
            imageDataDone = true;
            if (image->defect()) return *image->defect();
            if (!image->complete()) return "IDAT: not enough image data";
        }

        // The chunk's data, in pieces; the CRC covers type and data.
        uLong crc = crc32(0L, head + 4, 4);
        const bool keep = type == tag("IHDR");
        data.clear();
        std::uint32_t left = length;
        while (left > 0) {
            const std::uint32_t n = std::min<std::uint32_t>(left, piece.size());
            in.read(reinterpret_cast<char*>(piece.data()), n);
            if (in.gcount() != static_cast<std::streamsize>(n))
                return name + ": the file ends inside the chunk (truncated)";
            crc = crc32(crc, piece.data(), n);
            if (keep) data.insert(data.end(), piece.data(), piece.data() + n);
            if (inImageData) image->feed(piece.data(), n);
            left -= n;
        }
        if (inImageData && image->defect()) return *image->defect();
        unsigned char stored[4];
        in.read(reinterpret_cast<char*>(stored), 4);
        if (in.gcount() != 4) return name + ": the file ends before the chunk's CRC (truncated)";
        // libpng stops at a critical chunk's bad CRC and only warns for an ancillary one.
        if (critical && bigEndian(stored) != static_cast<std::uint32_t>(crc))
            return name + ": CRC error";

        if (type == tag("IHDR")) {
            if (header) return "a second IHDR";
            if (length != 13) return "IHDR is not 13 bytes long";
            if (auto bad = headerDefect(data.data())) return *bad;
            header = headerOf(data.data());
        } else if (type == tag("PLTE")) {
            if (havePalette) return "a second PLTE";
            // libpng ignores a bad or late palette in a colour image, not in a palette one.
            if (header->colorType == 3 && !imageDataDone && !inImageData &&
                (length == 0 || length > 3 * 256 || length % 3 != 0))
                return "PLTE of " + std::to_string(length) + " bytes";
            havePalette = true;
        } else if (type == tag("IEND")) {
            if (!imageDataDone) return "no IDAT before IEND";
            break;
        } else if (critical && type != tag("IDAT")) {
            return "unknown critical chunk " + name;
        }
    }
    return std::nullopt;
}

}  // namespace microrelief
