#include "microrelief/io/PyramidFile.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <utility>

#include "io/CheckedImageInput.h"
#include "io/PngCheck.h"
#if MICRORELIEF_WITH_GDAL
#include "io/DemFile.h"
#endif
#include "microrelief/core/Error.h"
#include "microrelief/core/Machine.h"
#include "microrelief/io/AtomicFile.h"

namespace microrelief {

namespace {

constexpr char kMagic[8] = {'M', 'R', 'P', 'Y', 'R', 'A', 'M', 'D'};
// Version 2 (2026-12-04) added the georeference; a cache builds a file of version 1 again.
constexpr std::uint32_t kVersion = 2;
constexpr std::size_t kFixedBytes = 52;  // magic to the georeference's length
constexpr std::uint64_t kAlign = 4096;
// The largest side a pyramid file may have: the programs' (65536). With pages of at least
// 16^2 that is at most 22.4 million pages, a page table of 90 MB: the most a crafted
// header can make the reader allocate before its CRC is checked. Every count and offset
// below fits 64 bits.
constexpr std::uint32_t kMaxSide = kMaxPagedHeightMapSide;
constexpr std::uint32_t kMaxKeyBytes = 1u << 16;
constexpr std::uint32_t kMaxGeoreferenceBytes = 1u << 16;

std::uint32_t crcOf(const void* data, std::size_t size) {
    return static_cast<std::uint32_t>(
        crc32_z(crc32_z(0L, Z_NULL, 0), static_cast<const Bytef*>(data), size));
}

void put32(std::vector<unsigned char>& bytes, std::size_t at, std::uint32_t value) {
    for (int k = 0; k < 4; ++k) bytes[at + k] = static_cast<unsigned char>(value >> (8 * k));
}
void put64(std::vector<unsigned char>& bytes, std::size_t at, std::uint64_t value) {
    for (int k = 0; k < 8; ++k) bytes[at + k] = static_cast<unsigned char>(value >> (8 * k));
}
std::uint32_t get32(const unsigned char* bytes) {
    std::uint32_t value = 0;
    for (int k = 0; k < 4; ++k) value |= static_cast<std::uint32_t>(bytes[k]) << (8 * k);
    return value;
}
std::uint64_t get64(const unsigned char* bytes) {
    std::uint64_t value = 0;
    for (int k = 0; k < 8; ++k) value |= static_cast<std::uint64_t>(bytes[k]) << (8 * k);
    return value;
}

// Pages a side each page level has, and where each level's first page is.
struct PageGrid {
    std::vector<glm::ivec2> across;  // per page level
    std::vector<int> first;
    std::uint64_t count = 0;
};
PageGrid pageGrid(int width, int height, int shift) {
    const std::vector<glm::ivec2> windows = windowLevelSizes(width, height);
    PageGrid grid;
    for (std::size_t level = 0; level <= windows.size(); ++level) {
        const glm::ivec2 size = windows[level > 0 ? level - 1 : 0];
        const glm::ivec2 across = (size + (1 << shift) - 1) >> shift;
        grid.across.push_back(across);
        grid.first.push_back(static_cast<int>(grid.count));
        grid.count += static_cast<std::uint64_t>(across.x) * across.y;
    }
    return grid;
}

// Where the pages start after a header whose key and georeference take `textBytes`.
std::uint64_t dataOffsetFor(std::size_t textBytes, std::uint64_t pages) {
    const std::uint64_t header = kFixedBytes + textBytes + 4 * pages + 4;
    return (header + kAlign - 1) / kAlign * kAlign;
}

std::string errnoText() {
    return std::strerror(errno);
}

// A georeference as the header keeps it: `name=value` lines, the numbers in the shortest
// form that reads back to the same double; empty for none.
std::string georeferenceText(const std::optional<Georeference>& geo) {
    if (!geo) return {};
    std::string text;
    const auto number = [&](const char* name, double value) {
        char digits[32];
        const auto end = std::to_chars(digits, digits + sizeof digits, value).ptr;
        text += std::string(name) + "=" + std::string(digits, end) + "\n";
    };
    number("sample_width_m", geo->sampleWidthMetres);
    number("sample_height_m", geo->sampleHeightMetres);
    number("lowest_m", geo->lowestMetres);
    number("highest_m", geo->highestMetres);
    number("semi_major_m", geo->semiMajorMetres);
    number("semi_minor_m", geo->semiMinorMetres);
    text += "geographic=" + std::to_string(geo->geographic ? 1 : 0) + "\n";
    text += "global=" + std::to_string(geo->global ? 1 : 0) + "\n";
    text += "nodata_samples=" + std::to_string(geo->nodataSamples) + "\n";
    std::string crs = geo->crs;
    std::replace(crs.begin(), crs.end(), '\n', ' ');
    return text + "crs=" + crs + "\n";
}

// georeferenceText read back; nullopt where `text` is not one (the header's CRC-32 has
// passed, so only a writer's mistake gets there).
std::optional<Georeference> parseGeoreference(const std::string& text) {
    Georeference geo;
    std::size_t at = 0;
    const auto field = [&](const char* name) -> std::optional<std::string> {
        const std::string prefix = std::string(name) + "=";
        const std::size_t end = text.find('\n', at);
        if (end == std::string::npos || text.compare(at, prefix.size(), prefix) != 0)
            return std::nullopt;
        std::string value = text.substr(at + prefix.size(), end - at - prefix.size());
        at = end + 1;
        return value;
    };
    const auto number = [&](const char* name, auto& value) {
        const std::optional<std::string> digits = field(name);
        if (!digits) return false;
        const auto [end, error] =
            std::from_chars(digits->data(), digits->data() + digits->size(), value);
        return error == std::errc() && end == digits->data() + digits->size();
    };
    int geographic = 0, global = 0;
    if (!number("sample_width_m", geo.sampleWidthMetres) ||
        !number("sample_height_m", geo.sampleHeightMetres) ||
        !number("lowest_m", geo.lowestMetres) || !number("highest_m", geo.highestMetres) ||
        !number("semi_major_m", geo.semiMajorMetres) ||
        !number("semi_minor_m", geo.semiMinorMetres) || !number("geographic", geographic) ||
        !number("global", global) || !number("nodata_samples", geo.nodataSamples))
        return std::nullopt;
    const std::optional<std::string> crs = field("crs");
    if (!crs || at != text.size()) return std::nullopt;
    geo.geographic = geographic == 1;
    geo.global = global == 1;
    geo.crs = *crs;
    return geo;
}

}  // namespace

void writePyramidFile(const std::filesystem::path& file, const MapRows& rows, bool wrapU,
                      const std::string& sourceKey, const std::string& source, int pageSide,
                      const BuildProgress& progress,
                      const std::optional<Georeference>& georeference) {
    if (pageSide < 16 || pageSide > 4096 || (pageSide & (pageSide - 1)) != 0)
        throwRuntime("writePyramidFile: the page side must be a power of two from 16 to 4096");
    if (sourceKey.size() > kMaxKeyBytes) throwRuntime("writePyramidFile: a source key too long");
    const std::string geoText = georeferenceText(georeference);
    if (geoText.size() > kMaxGeoreferenceBytes)
        throwRuntime("writePyramidFile: a georeference too long");
    const std::string text = sourceKey + geoText;  // as the header holds them
    if (rows.width < 1 || rows.height < 1 || static_cast<std::uint32_t>(rows.width) > kMaxSide ||
        static_cast<std::uint32_t>(rows.height) > kMaxSide) {
        throwBadInput(source + ": " + std::to_string(rows.width) + " x " +
                      std::to_string(rows.height) + " samples; a pyramid file holds 1 to " +
                      std::to_string(kMaxSide) + " a side");
    }
    const int shift = std::countr_zero(static_cast<unsigned>(pageSide));
    const PageGrid grid = pageGrid(rows.width, rows.height, shift);
    if (grid.count > static_cast<std::uint64_t>(std::numeric_limits<int>::max()))
        throwBadInput(source + ": too many pages for a pyramid file");
    const std::uint64_t pageBytes = std::uint64_t{4} << (2 * shift);
    const std::uint64_t dataOffset = dataOffsetFor(text.size(), grid.count);
    std::vector<std::uint32_t> crcs(grid.count, 0u);

    FileWriteBatch batch;
    StagedFile& out = batch.stage(file);
    // Each page level's band of rows, cut into pages when full or at the level's last row.
    const std::vector<glm::ivec2> windows = windowLevelSizes(rows.width, rows.height);
    std::vector<std::vector<float>> bands(grid.across.size());
    std::vector<float> page(static_cast<std::size_t>(pageSide) * pageSide);
    const PyramidRowSink sink = [&](int level, int row, const float* texels) {
        const glm::ivec2 size = windows[level > 0 ? level - 1 : 0];
        std::vector<float>& band = bands[level];
        band.resize(static_cast<std::size_t>(size.x) * pageSide);
        const int inBand = row & (pageSide - 1);
        std::copy_n(texels, size.x, band.begin() + static_cast<std::ptrdiff_t>(inBand) * size.x);
        if (inBand != pageSide - 1 && row != size.y - 1) return;
        const int rowsHere = inBand + 1;
        const int pageRow = row >> shift;
        for (int px = 0; px < grid.across[level].x; ++px) {
            std::fill(page.begin(), page.end(), 0.0f);
            const int x0 = px << shift, columns = std::min(pageSide, size.x - x0);
            for (int y = 0; y < rowsHere; ++y) {
                std::copy_n(band.begin() + static_cast<std::ptrdiff_t>(y) * size.x + x0, columns,
                            page.begin() + static_cast<std::ptrdiff_t>(y) * pageSide);
            }
            const std::uint64_t id =
                grid.first[level] + static_cast<std::uint64_t>(pageRow) * grid.across[level].x + px;
            crcs[id] = crcOf(page.data(), pageBytes);
            out.writeAt(page.data(), pageBytes, dataOffset + id * pageBytes);
        }
        if (row == size.y - 1) std::vector<float>().swap(band);  // the level is done
    };
    const StreamedPyramid streamed = streamPyramid(rows, wrapU, pageSide, sink, source, progress);

    std::vector<unsigned char> header(kFixedBytes + text.size() + 4 * grid.count + 4, 0);
    std::memcpy(header.data(), kMagic, sizeof kMagic);
    put32(header, 8, kVersion);
    put32(header, 12, static_cast<std::uint32_t>(rows.width));
    put32(header, 16, static_cast<std::uint32_t>(rows.height));
    put32(header, 20, wrapU ? 1u : 0u);
    put32(header, 24, static_cast<std::uint32_t>(shift));
    put32(header, 28, std::bit_cast<std::uint32_t>(streamed.largestSample));
    put32(header, 32, static_cast<std::uint32_t>(sourceKey.size()));
    put32(header, 36, static_cast<std::uint32_t>(grid.count));
    put64(header, 40, dataOffset);
    put32(header, 48, static_cast<std::uint32_t>(geoText.size()));
    std::memcpy(header.data() + kFixedBytes, text.data(), text.size());
    for (std::uint64_t k = 0; k < grid.count; ++k)
        put32(header, kFixedBytes + text.size() + 4 * k, crcs[k]);
    const std::size_t crcAt = header.size() - 4;
    put32(header, crcAt, crcOf(header.data(), crcAt));
    out.writeAt(header.data(), header.size(), 0);
    out.finish();
    batch.commit();
}

std::shared_ptr<const PyramidFile> PyramidFile::open(const std::filesystem::path& file) {
    const std::string name = file.string();
    checkRegularFile(file, name);
    // O_NONBLOCK: a FIFO put there since the check would hold open(2) until a writer came.
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throwBadInput(name + ": cannot open (" + errnoText() + ")");
    struct Closer {
        int fd;
        bool keep = false;
        ~Closer() {
            if (!keep) ::close(fd);
        }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) throwBadInput(name + ": cannot stat (" + errnoText() + ")");
    if (!S_ISREG(st.st_mode))
        throwBadInput(name + ": is not a regular file (a FIFO, device or socket)");
    const auto fileBytes = static_cast<std::uint64_t>(st.st_size);
    const auto readExactly = [&](void* to, std::size_t size, std::uint64_t at) {
        auto* bytes = static_cast<unsigned char*>(to);
        for (std::size_t done = 0; done < size;) {
            const ssize_t got =
                ::pread(fd, bytes + done, size - done, static_cast<off_t>(at + done));
            if (got < 0 && errno == EINTR) continue;
            if (got <= 0)
                throwBadInput(name +
                              ": cannot read its header (truncated); delete it to build "
                              "it again");
            done += static_cast<std::size_t>(got);
        }
    };
    const std::string notOurs = name + ": not a microrelief pyramid file";
    const std::string rebuild = "; delete it to build it again";
    if (fileBytes < kFixedBytes)
        throwBadInput(notOurs + " (" + std::to_string(fileBytes) + " bytes)" + rebuild);
    std::vector<unsigned char> header(kFixedBytes);
    readExactly(header.data(), kFixedBytes, 0);
    if (std::memcmp(header.data(), kMagic, sizeof kMagic) != 0) throwBadInput(notOurs + rebuild);
    if (const std::uint32_t version = get32(&header[8]); version != kVersion) {
        throwBadInput(name + ": a pyramid file of version " + std::to_string(version) +
                      "; this build reads version " + std::to_string(kVersion) +
                      " (delete it to build it again)");
    }
    const std::uint32_t width = get32(&header[12]), height = get32(&header[16]),
                        wrap = get32(&header[20]), shift = get32(&header[24]),
                        keyBytes = get32(&header[32]), pages = get32(&header[36]),
                        geoBytes = get32(&header[48]);
    const float largest = std::bit_cast<float>(get32(&header[28]));
    const std::uint64_t dataOffset = get64(&header[40]);
    const std::string corrupt = name + ": the pyramid file's header is corrupt";
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide || wrap > 1 || shift < 4 ||
        shift > 12 || keyBytes > kMaxKeyBytes || geoBytes > kMaxGeoreferenceBytes ||
        !(std::isfinite(largest) && largest >= 0.0f))
        throwBadInput(corrupt + rebuild);
    const PageGrid grid =
        pageGrid(static_cast<int>(width), static_cast<int>(height), static_cast<int>(shift));
    const std::size_t textBytes = std::size_t{keyBytes} + geoBytes;
    if (grid.count != pages || dataOffset != dataOffsetFor(textBytes, pages))
        throwBadInput(corrupt + rebuild);
    const std::uint64_t pageBytes = std::uint64_t{4} << (2 * shift);
    const std::uint64_t expected = dataOffset + pages * pageBytes;
    if (fileBytes != expected) {
        throwBadInput(name + ": " + std::to_string(fileBytes) + " bytes where its header says " +
                      std::to_string(expected) + (fileBytes < expected ? " (truncated)" : "") +
                      rebuild);
    }
    header.resize(kFixedBytes + textBytes + 4 * std::size_t{pages} + 4);
    readExactly(header.data() + kFixedBytes, header.size() - kFixedBytes, kFixedBytes);
    const std::size_t crcAt = header.size() - 4;
    if (get32(&header[crcAt]) != crcOf(header.data(), crcAt))
        throwBadInput(corrupt + " (its CRC-32 differs)" + rebuild);
    const char* const text = reinterpret_cast<const char*>(header.data()) + kFixedBytes;
    std::string key(text, keyBytes);
    std::optional<Georeference> georeference;
    if (geoBytes > 0) {
        georeference = parseGeoreference(std::string(text + keyBytes, geoBytes));
        if (!georeference) throwBadInput(corrupt + " (its georeference)" + rebuild);
    }
    std::vector<std::uint32_t> crcs(pages);
    for (std::uint32_t k = 0; k < pages; ++k)
        crcs[k] = get32(&header[kFixedBytes + textBytes + 4 * k]);
    std::shared_ptr<const PyramidFile> opened(
        new PyramidFile(file, fd, static_cast<int>(width), static_cast<int>(height), wrap == 1,
                        largest, static_cast<int>(shift), std::move(key), std::move(georeference),
                        std::move(crcs), dataOffset));
    closer.keep = true;  // the file's now: closed with it
    return opened;
}

PyramidFile::PyramidFile(const std::filesystem::path& path, int fd, int width, int height,
                         bool wrapU, float largestSample, int shift, std::string sourceKey,
                         std::optional<Georeference> georeference, std::vector<std::uint32_t> crcs,
                         std::uint64_t dataOffset)
    : PyramidPages(width, height, wrapU, largestSample),
      path_(path),
      fd_(fd),
      shift_(shift),
      sourceKey_(std::move(sourceKey)),
      georeference_(std::move(georeference)),
      crcs_(std::move(crcs)),
      firstPage_(pageGrid(width, height, shift).first),
      dataOffset_(dataOffset) {}

PyramidFile::~PyramidFile() {
    ::close(fd_);
}

void PyramidFile::readPage(int page, std::vector<float>& texels) const {
    const std::size_t bytes = std::size_t{4} << (2 * shift_);
    texels.resize(bytes / 4);
    auto* to = reinterpret_cast<unsigned char*>(texels.data());
    const std::uint64_t at = dataOffset_ + static_cast<std::uint64_t>(page) * bytes;
    for (std::size_t done = 0; done < bytes;) {
        const ssize_t got = ::pread(fd_, to + done, bytes - done, static_cast<off_t>(at + done));
        if (got < 0 && errno == EINTR) continue;
        if (got < 0)
            throwRuntime(path_.string() + ": cannot read page " + std::to_string(page) + " (" +
                         errnoText() + ")");
        if (got == 0)
            throwBadInput(path_.string() + ": page " + std::to_string(page) +
                          " lies past the file's end (truncated since it was opened)");
        done += static_cast<std::size_t>(got);
    }
    if (crcOf(texels.data(), bytes) != crcs_[page]) {
        int level = static_cast<int>(firstPage_.size()) - 1;
        while (level > 0 && firstPage_[level] > page) --level;
        throwBadInput(path_.string() + ": page " + std::to_string(page) + " (page level " +
                      std::to_string(level) +
                      ") is corrupt: its CRC-32 differs from the "
                      "header's; delete the file to build it again");
    }
}

void PyramidFile::read(int level, const TexelRect& rect, float* out) const {
    const int side = pageSide();
    const glm::ivec2 size = levelSize(level);
    const int across = (size.x + side - 1) >> shift_;
    std::vector<float> texels;
    for (int py = rect.y0 >> shift_; py <= (rect.y1 - 1) >> shift_; ++py) {
        for (int px = rect.x0 >> shift_; px <= (rect.x1 - 1) >> shift_; ++px) {
            readPage(firstPage_[level] + py * across + px, texels);
            const TexelRect part{std::max(rect.x0, px << shift_), std::max(rect.y0, py << shift_),
                                 std::min(rect.x1, (px + 1) << shift_),
                                 std::min(rect.y1, (py + 1) << shift_)};
            for (int y = part.y0; y < part.y1; ++y) {
                std::copy_n(texels.begin() +
                                static_cast<std::ptrdiff_t>(y - (py << shift_)) * side +
                                (part.x0 - (px << shift_)),
                            part.width(),
                            out + static_cast<std::ptrdiff_t>(y - rect.y0) * rect.width() +
                                (part.x0 - rect.x0));
            }
        }
    }
}

std::string pyramidSourceKey(const std::filesystem::path& mapFile,
                             const HeightMapLoadOptions& options, bool wrapU) {
    std::error_code error;
    const std::filesystem::path path = std::filesystem::weakly_canonical(mapFile, error);
    struct stat st {};
    if (::stat(mapFile.c_str(), &st) != 0)
        throwBadInput(mapFile.string() + ": cannot read (" + errnoText() + ")");
    const auto ns = [](const timespec& t) {
        return std::to_string(static_cast<long long>(t.tv_sec) * 1000000000LL + t.tv_nsec);
    };
    // The change time too: a copy that keeps the time (cp -p, rsync -t) or `touch -r` sets
    // the modification time back, never the change time.
    return "map=" + (error ? mapFile.string() : path.string()) +
           "\nbytes=" + std::to_string(st.st_size) + "\nmtime_ns=" + ns(st.st_mtim) +
           "\nctime_ns=" + ns(st.st_ctim) + "\ninode=" + std::to_string(st.st_ino) +
           "\nchannel=" + std::to_string(options.channel) +
           "\nnormalize=" + (options.normalize ? "1" : "0") + "\nwrap_u=" + (wrapU ? "1" : "0");
}

MapFileRows heightMapFileRows(const std::filesystem::path& file,
                              const HeightMapLoadOptions& options, const BuildProgress& firstPass) {
    const std::string name = file.string();
    checkRegularFile(file, name);
#if MICRORELIEF_WITH_GDAL
    if (isElevationModelFile(file)) {
        DemRows dem = demRows(file, options, firstPass);
        return {std::move(dem.rows), dem.georeference};
    }
#endif
    // An interlaced PNG cannot be read by rows: OpenImageIO decodes it whole at its first
    // row (8 or 16 bits a channel, a palette as RGBA at most). Refused where that is more
    // than half the memory available, which is what the rows are for.
    std::string pngDefect;
    if (const std::optional<PngHeader> png =
            hasPngSignature(file) ? readPngHeader(file, pngDefect) : std::nullopt;
        png && png->interlaced) {
        const std::uint64_t channels = png->colorType == 0   ? 1
                                       : png->colorType == 4 ? 2
                                       : png->colorType == 2 ? 3
                                                             : 4;
        const std::uint64_t bytes =
            std::uint64_t{png->width} * png->height * channels * (png->bitDepth == 16 ? 2 : 1);
        const std::uint64_t memory = availableMemoryBytes();
        if (memory > 0 && bytes > memory / 2) {
            throwBadInput(name + ": an interlaced PNG, which is decoded whole (" +
                          std::to_string(bytes >> 20) + " MiB, more than half of the " +
                          std::to_string(memory >> 20) +
                          " MiB available now) where its rows are needed; save it without "
                          "interlacing (for example as a tiled TIFF: oiiotool in.png --tile 256 "
                          "256 -o out.tif)");
        }
    }
    struct State {
        std::filesystem::path file;
        HeightMapLoadOptions options;
        std::unique_ptr<OIIO::ImageInput> input;
        int next = 0;  // the next row the open input gives
        float lo = 0.0f, scale = 1.0f;
        bool normalize = false;
    };
    auto state = std::make_shared<State>();
    state->file = file;
    state->options = options;
    const auto open = [state, name] {
        state->input = openCheckedImage(state->file, state->options.maxSide, "a height map",
                                        state->options.maxSamples);
        const OIIO::ImageSpec& spec = state->input->spec();
        if (spec.depth > 1) throwBadInput(name + ": volume images are not height maps");
        if (state->options.channel < 0 || state->options.channel >= spec.nchannels) {
            throwBadInput(name + ": {map.load.channel} " + std::to_string(state->options.channel) +
                          " is out of range; the image has " + std::to_string(spec.nchannels) +
                          " channel(s)");
        }
        state->next = 0;
    };
    // Rows y0 .. y1 - 1 as stored (reading as FLOAT makes OpenImageIO normalise integer
    // formats by their type range and pass floats through), rows of the data window from
    // its first. A tiled image (TIFF, OpenEXR) by the rows of tiles that cover them
    // (OpenImageIO 2.4 divides by zero reading scanlines of one); a scanline image in order,
    // from the top again (opened anew) for a row the input has passed.
    const auto readStored = [state, name, open](int y0, int y1, float* out) {
        if (!state->input || y0 < state->next) open();
        const OIIO::ImageSpec& spec = state->input->spec();
        const int width = spec.width, channel = state->options.channel;
        bool ok = false;
        if (spec.tile_width > 0) {
            const int tile = std::max(spec.tile_height, 1);
            const int t0 = y0 / tile * tile,
                      t1 = std::min(spec.height, (y1 + tile - 1) / tile * tile);
            std::vector<float> tiles(static_cast<std::size_t>(width) * (t1 - t0));
            ok = state->input->read_tiles(0, 0, spec.x, spec.x + width, spec.y + t0, spec.y + t1,
                                          spec.z, spec.z + std::max(spec.depth, 1), channel,
                                          channel + 1, OIIO::TypeDesc::FLOAT, tiles.data());
            if (ok) {
                std::copy(tiles.begin() + static_cast<std::ptrdiff_t>(y0 - t0) * width,
                          tiles.begin() + static_cast<std::ptrdiff_t>(y1 - t0) * width, out);
            }
        } else {
            ok = state->input->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, channel,
                                              channel + 1, OIIO::TypeDesc::FLOAT, out);
        }
        if (!ok) {
            const std::string reason = oneLine(state->input->geterror());
            throwBadInput(name + ": cannot read rows " + std::to_string(y0) + " to " +
                          std::to_string(y1 - 1) + " (" +
                          (reason.empty() ? "truncated or corrupt" : reason) + ")");
        }
        state->next = y1;
    };
    open();
    MapRows rows;
    rows.width = state->input->spec().width;
    rows.height = state->input->spec().height;
    if (options.normalize) {
        // A pass of its own for [min, max], as prepareHeights maps them.
        float lo = INFINITY, hi = -INFINITY;
        std::vector<float> band(static_cast<std::size_t>(rows.width) * 256);
        for (int y0 = 0; y0 < rows.height; y0 += 256) {
            const int y1 = std::min(rows.height, y0 + 256);
            readStored(y0, y1, band.data());
            for (std::size_t k = 0; k < static_cast<std::size_t>(y1 - y0) * rows.width; ++k) {
                if (!std::isfinite(band[k])) {
                    throwBadInput(name +
                                  ": the height map holds a non-finite value (NaN or Inf); "
                                  "{map.load.normalize} cannot map it");
                }
                lo = std::min(lo, band[k]);
                hi = std::max(hi, band[k]);
            }
            if (firstPass) firstPass(y1, rows.height);
        }
        state->normalize = true;
        state->lo = lo;
        state->scale = hi - lo;
    }
    rows.read = [state, readStored, width = rows.width](int y0, int y1, float* out) {
        readStored(y0, y1, out);
        if (!state->normalize) return;
        const std::size_t count = static_cast<std::size_t>(y1 - y0) * width;
        for (std::size_t k = 0; k < count; ++k)
            out[k] = state->scale > 0.0f ? (out[k] - state->lo) / state->scale : 0.0f;
    };
    return {rows, std::nullopt};
}

namespace {

// Whether `file` is a pyramid file of another version than this build's (a cache rebuilds
// it; PyramidFile::open refuses it).
// Opened without blocking and asked what it is before a byte is read: a FIFO there (or a
// link to one) would hold a plain open(2) until a writer came.
bool otherVersion(const std::filesystem::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return false;
    struct stat st {};
    unsigned char head[12] = {};
    const bool other = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) &&
                       ::pread(fd, head, sizeof head, 0) == static_cast<ssize_t>(sizeof head) &&
                       std::memcmp(head, kMagic, sizeof kMagic) == 0 && get32(head + 8) != kVersion;
    ::close(fd);
    return other;
}

// The map's stem as the start of its pyramid file's name, cut to at most 128 bytes (at a
// character's start): with the hash and the extension the name stays within the 255 bytes
// a file system allows, whatever the map is called.
std::string stemForName(const std::filesystem::path& mapFile) {
    std::string stem = mapFile.stem().string();
    if (stem.size() <= 128) return stem;
    std::size_t end = 128;
    while (end > 0 && (static_cast<unsigned char>(stem[end]) & 0xC0) == 0x80) --end;
    return stem.substr(0, end);
}

}  // namespace

std::shared_ptr<const PyramidFile> openOrBuildPyramidFile(const std::filesystem::path& mapFile,
                                                          const std::filesystem::path& cacheFolder,
                                                          const HeightMapLoadOptions& options,
                                                          bool wrapU, const BuildProgress& progress,
                                                          bool* built) {
    checkRegularFile(mapFile, mapFile.string());
    const std::string key = pyramidSourceKey(mapFile, options, wrapU);
    // One file per map and load options: the map's name and a hash of its key but for the
    // size and time (so that a changed map replaces its stale pyramid).
    const std::string identity =
        key.substr(0, key.find("\nbytes=")) + key.substr(key.find("\nchannel="));
    std::uint64_t fnv = 14695981039346656037ull;  // FNV-1a: the same name on every build
    for (const unsigned char c : identity) fnv = (fnv ^ c) * 1099511628211ull;
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv));
    const std::filesystem::path file = cacheFolder / (stemForName(mapFile) + "-" + hash + ".mrpyr");
    if (built) *built = false;
    std::error_code error;
    // What is there, asked with error codes: a name too long or a folder that cannot be
    // searched is said in one line, not as std::filesystem's exception.
    const std::filesystem::file_status folder = std::filesystem::status(cacheFolder, error);
    if (folder.type() != std::filesystem::file_type::not_found && error) {
        throwBadInput(cacheFolder.string() + ": cannot be the pyramid files' cache (" +
                      error.message() + ")");
    }
    if (std::filesystem::exists(folder) && !std::filesystem::is_directory(folder))
        throwBadInput(cacheFolder.string() + ": is not a folder (the pyramid files' cache)");
    // The folder is made, if missing, by the build's own staging (writePyramidFile's
    // FileWriteBatch), which takes it away again when the build fails or is interrupted:
    // a failed run leaves no folder it made (docs/cli.md).
    // A build killed before its rename (SIGKILL, a power cut) left its temporary: gone, and
    // the build starts again.
    for (const auto& entry : std::filesystem::directory_iterator(cacheFolder, error)) {
        if (abandonedTemporaryTarget(entry.path()) == file)
            std::filesystem::remove(entry.path(), error);
    }
    // Its kind before anything opens it: a FIFO there (or a link to one) is refused, not
    // waited on; a folder or device likewise.
    const std::filesystem::file_status there = std::filesystem::status(file, error);
    if (there.type() != std::filesystem::file_type::not_found && error)
        throwBadInput(file.string() + ": cannot read (" + error.message() + ")");
    if (std::filesystem::exists(there) && !std::filesystem::is_regular_file(there)) {
        throwBadInput(file.string() +
                      ": is not a regular file (a folder, FIFO, device or socket) where the "
                      "map's pyramid file goes; remove it");
    }
    if (std::filesystem::exists(there) && !otherVersion(file)) {
        std::shared_ptr<const PyramidFile> found = PyramidFile::open(file);
        if (found->sourceKey() == key) return found;
    }
    // One count for the user: a first pass of the map's (a DEM's range, --normalize's) where
    // it makes one, then the two of the stream.
    long long firstRows = 0;
    BuildProgress firstPass, streamed;
    if (progress) {
        firstPass = [&](long long done, long long total) {
            firstRows = total;
            progress(done, 3 * total);
        };
        streamed = [&](long long done, long long total) {
            progress(firstRows + done, firstRows + total);
        };
    }
    const MapFileRows source = heightMapFileRows(mapFile, options, firstPass);
    writePyramidFile(file, source.rows, wrapU, key, mapFile.string(), kPyramidFilePageSide,
                     streamed, source.georeference);
    if (built) *built = true;
    return PyramidFile::open(file);
}

}  // namespace microrelief
