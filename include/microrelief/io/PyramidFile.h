// A map's samples and max pyramid on disk, in square pages (the microrelief::io component):
// what a map larger than memory is drawn from (gl/PagedPyramid.h reads it as PyramidPages).
// Built once from the map's rows in bounded memory (core/heightmap/PyramidStream.h), reused
// while the map file is unchanged (openOrBuildPyramidFile), its pages the texels of
// MaxPyramid(map, wrapU, BoundPrecision::Half), bit for bit.
//
// The file (docs/terrain.md, "Pyramid files"), little-endian:
//   header   "MRPYRAMD", version, W, H, wrapU, log2 page side, the largest sample, the
//            source key's length, the page count, the pages' offset (u64), the
//            georeference's length, the source key (what the file was built from: path,
//            size, time and load options), the georeference of an elevation model (text,
//            `name=value` lines; empty for an image), a CRC-32 of each page, and a CRC-32
//            of all that;
//   pages    fixed-size side x side floats from the offset on (4 KiB aligned): level 0
//            (the samples), then window levels 0, 1, ... down to 1 x 1, each row-major
//            in pages, texels past a level's edge 0.
// Why not a tiled TIFF or OpenEXR: the build writes every level at once, a band of rows
// at a time, where those containers write their levels (parts, directories) one after
// another; and neither checks an uncompressed tile. Here each page is read with one pread
// and refused when its CRC-32 differs; a file whose size is not the header's is refused
// when opened.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/heightmap/PyramidPages.h"
#include "microrelief/core/heightmap/PyramidStream.h"
#include "microrelief/core/scene/Georeference.h"

namespace microrelief {

// The page side pyramid files are built with.
inline constexpr int kPyramidFilePageSide = 256;

// Progress of a long build: rows done out of total (PyramidStream's two passes).
using BuildProgress = std::function<void(long long done, long long total)>;

// Builds the pyramid file of `rows` (named `source` in messages) at `file`, whole or not at
// all (io/AtomicFile.h: a temporary renamed into place, removed on errors and signals).
// `sourceKey` and the map's `georeference` (an elevation model's) are kept in it
// (PyramidFile::sourceKey, georeference). Throws Error(BadInput) for a bad sample,
// Error(Runtime) when the file cannot be written.
void writePyramidFile(const std::filesystem::path& file, const MapRows& rows, bool wrapU,
                      const std::string& sourceKey, const std::string& source,
                      int pageSide = kPyramidFilePageSide, const BuildProgress& progress = {},
                      const std::optional<Georeference>& georeference = std::nullopt);

class PyramidFile final : public PyramidPages {
public:
    // Opens `file`: refuses (Error(BadInput) naming it) one that is not a regular file, not
    // a pyramid file, of another version, whose header is corrupt, or whose size is not
    // what its header says (truncated). Reads the header alone.
    static std::shared_ptr<const PyramidFile> open(const std::filesystem::path& file);
    ~PyramidFile() override;

    // Reads the pages `rect` covers; Error(BadInput) naming the file and the page for one
    // whose CRC-32 is not the header's (corrupt), Error(Runtime) for a failed read.
    void read(int level, const TexelRect& rect, float* out) const override;

    const std::string& sourceKey() const { return sourceKey_; }
    // The map's georeference where it is an elevation model (io/HeightMapFile.h).
    const std::optional<Georeference>& georeference() const { return georeference_; }
    int pageSide() const { return 1 << shift_; }
    int pageCount() const { return static_cast<int>(crcs_.size()); }
    const std::filesystem::path& path() const { return path_; }

private:
    PyramidFile(const std::filesystem::path& path, int fd, int width, int height, bool wrapU,
                float largestSample, int shift, std::string sourceKey,
                std::optional<Georeference> georeference, std::vector<std::uint32_t> crcs,
                std::uint64_t dataOffset);
    void readPage(int page, std::vector<float>& texels) const;

    std::filesystem::path path_;
    int fd_;
    int shift_;
    std::string sourceKey_;
    std::optional<Georeference> georeference_;
    std::vector<std::uint32_t> crcs_;
    std::vector<int> firstPage_;  // per page level
    std::uint64_t dataOffset_;
};

// The key of a map file as it is now: its path, size, modification and change times and
// inode, the load options and the base's wrap. A pyramid file built with another key is
// stale.
std::string pyramidSourceKey(const std::filesystem::path& mapFile,
                             const HeightMapLoadOptions& options, bool wrapU);

// The rows of a height map file as loadHeightMapFile reads it, and its georeference where
// it has one. An image's (integers to [0, 1], floats as stored, options.channel;
// options.normalize maps [min, max] to [0, 1] from a first pass of its own) are read a band
// of scanlines (or of tiles) at a time through OpenImageIO and never held whole, but where
// OpenImageIO holds it (an interlaced PNG). An elevation model's (a GeoTIFF grid, an .hgt
// file, where the io component reads them through GDAL) a block of rows at a time, after a
// first pass for its heights' range. The header is checked at once (options.maxSide,
// maxSamples; a file that is not regular refused); the reads throw Error(BadInput) naming
// the file. `firstPass` (may be empty) is told the rows read so far, out of the height, by
// a first pass (a DEM's range, --normalize's); none is made for an image as stored.
struct MapFileRows {
    MapRows rows;
    std::optional<Georeference> georeference;
};
MapFileRows heightMapFileRows(const std::filesystem::path& file,
                              const HeightMapLoadOptions& options,
                              const BuildProgress& firstPass = {});

// The pyramid file of `mapFile` in `cacheFolder` (made where missing; Error(BadInput) where
// it is a file): opened where one built from the map as it is now (pyramidSourceKey) is
// there, else built from its rows (heightMapFileRows) and opened; a file of another version
// is built again, one that is corrupt refused. `built` (may be null) says which. `progress`
// hears the build's rows: a first pass of the map's where it makes one, then
// streamPyramid's two, as one count.
std::shared_ptr<const PyramidFile> openOrBuildPyramidFile(const std::filesystem::path& mapFile,
                                                          const std::filesystem::path& cacheFolder,
                                                          const HeightMapLoadOptions& options,
                                                          bool wrapU,
                                                          const BuildProgress& progress = {},
                                                          bool* built = nullptr);

}  // namespace microrelief
