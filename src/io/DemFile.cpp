#include "io/DemFile.h"

#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <string_view>
#include <vector>

#include "io/CheckedImageInput.h"
#include "microrelief/core/Error.h"
#include "microrelief/io/AtomicFile.h"

namespace microrelief {

namespace {

constexpr double kPi = 3.14159265358979323846;

// GDAL's messages stay off stderr while it reads; the last one (this thread's) goes into
// ours.
class QuietGdal {
public:
    QuietGdal() {
        // GDAL's default handler prints; once GDAL's TIFF driver is up it also hears libtiff's
        // messages for every TIFF the process reads (OpenImageIO's too, one libtiff): none may
        // reach stderr, where a program's error is its one line.
        static std::once_flag registered;
        std::call_once(registered, [] {
            CPLSetErrorHandler(CPLQuietErrorHandler);
            GDALAllRegister();
        });
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~QuietGdal() { CPLPopErrorHandler(); }
    QuietGdal(const QuietGdal&) = delete;
    QuietGdal& operator=(const QuietGdal&) = delete;

    static std::string lastError() {
        const std::string message = oneLine(CPLGetLastErrorMsg());
        return message.empty() ? "truncated or corrupt" : message;
    }
};

struct DatasetCloser {
    void operator()(GDALDataset* dataset) const { GDALClose(dataset); }
};

std::string lower(std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

// Metres per unit of the band's heights; refuses a unit it does not know.
double verticalUnit(const std::string& name, const std::string& unitText) {
    const std::string unit = lower(unitText);
    if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" ||
        unit == "meters")
        return 1.0;
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot")
        return 0.3048;
    if (unit == "us survey foot" || unit == "ftus" || unit == "us-ft" || unit == "foot_us")
        return 1200.0 / 3937.0;
    throwBadInput(name + ": heights in '" + unitText +
                  "', a unit microrelief does not know (metres, feet or US survey feet)");
}

// How a file's grid lies on the ground, and the map north up and east to the right
// (scene-and-cli.md: image row 0 is the far edge, -z, at the top of a view from above) that
// it is read as, sample for sample. GDAL's geotransform puts the corner of the file's
// sample (c, r) at x = gt[0] + c gt[1] + r gt[2], y = gt[3] + c gt[4] + r gt[5]: a grid
// whose rows and columns run along x and y, in either order and either direction (the
// eight turns and mirrors of a square), is read as it lies, its samples permuted; any
// other is refused.
struct NorthUpGrid {
    int width = 0, height = 0;  // the map's, north up
    // The file's columns are the map's rows (and its rows the map's columns): the grid is
    // transposed, or turned 90 or 270 degrees.
    bool transposed = false;
    // Then the map's columns run west where the file's run (before the flip) and its rows
    // north: each read in reverse.
    bool flipColumns = false, flipRows = false;
    // The map's own geotransform, north up: {x0, dx, 0, y0, 0, -dy}, dx and dy > 0.
    std::array<double, 6> geotransform{};
};

NorthUpGrid northUpGrid(const std::string& name, const double gt[6], int fileWidth,
                        int fileHeight) {
    for (int k = 0; k < 6; ++k)
        if (!std::isfinite(gt[k])) throwBadInput(name + ": its grid's geotransform is not finite");
    // A term counts as zero where it moves the samples by less than a millionth of one over
    // the whole map: rounding in a file's writer, not a turn.
    constexpr double kAxisTolerance = 1e-6;
    const auto along = [&](double main, double cross, int count) {
        return std::abs(cross) * count <= kAxisTolerance * std::abs(main);
    };
    NorthUpGrid grid;
    double columnStep = 0.0, rowStep = 0.0;  // x per map column, y per map row, before flips
    if (along(gt[1], gt[4], fileWidth) && along(gt[5], gt[2], fileHeight)) {
        columnStep = gt[1];
        rowStep = gt[5];
        grid.width = fileWidth;
        grid.height = fileHeight;
    } else if (along(gt[2], gt[5], fileHeight) && along(gt[4], gt[1], fileWidth)) {
        grid.transposed = true;
        columnStep = gt[2];  // the file's rows run along x
        rowStep = gt[4];     // and its columns along y
        grid.width = fileHeight;
        grid.height = fileWidth;
    } else {
        // The angles of the file's two steps from east; at right angles, a turn.
        const double degrees = 180.0 / kPi;
        const double column = std::atan2(gt[4], gt[1]) * degrees;
        const double row = std::atan2(gt[5], gt[2]) * degrees;
        const double between = std::remainder(row - column, 360.0);
        std::ostringstream message;
        message << name << ": its grid is ";
        if (std::abs(std::abs(between) - 90.0) > 1e-6) {
            message << "sheared (its rows and columns meet at " << std::abs(between)
                    << " degrees, not at right angles)";
        } else {
            // The turn that brings the column step east, to the nearest of its quarter turns.
            const double turn = std::remainder(column, 90.0);
            message << "turned " << std::abs(turn) << " degrees from north up";
        }
        throwBadInput(message.str() +
                      "; only a grid whose rows and columns run east-west and north-south "
                      "is read (turn it north up first: gdalwarp -r bilinear in.tif out.tif)");
    }
    if (!(columnStep != 0.0) || !(rowStep != 0.0))
        throwBadInput(name + ": its grid's sample size is zero");
    grid.flipColumns = columnStep < 0.0;
    grid.flipRows = rowStep > 0.0;
    // The north-west corner: where the file's corner is, moved across the map where it is
    // read in reverse.
    const double x0 = gt[0] + (grid.flipColumns ? columnStep * grid.width : 0.0);
    const double y0 = gt[3] + (grid.flipRows ? rowStep * grid.height : 0.0);
    grid.geotransform = {x0, std::abs(columnStep), 0.0, y0, 0.0, -std::abs(rowStep)};
    return grid;
}

// The ground size of a sample and what the grid is, from the map's north-up grid and the
// coordinate system. Refuses a latitude/longitude grid that is not on the Earth: one
// reaching past a pole, or spanning more than the 360 degrees of longitude, by more than
// half a sample (a grid of samples centred on the poles and the date line has its edges
// half a sample beyond them).
Georeference groundOf(const std::string& name, const NorthUpGrid& grid,
                      const OGRSpatialReference* srs) {
    Georeference geo;
    const std::array<double, 6>& gt = grid.geotransform;
    const double stepX = gt[1], stepY = -gt[5];
    if (!(stepX > 0.0) || !(stepY > 0.0) || !std::isfinite(stepX) || !std::isfinite(stepY))
        throwBadInput(name + ": its grid's sample size is zero or not finite");
    if (srs && srs->IsGeographic()) {
        geo.geographic = true;
        geo.semiMajorMetres = srs->GetSemiMajor();
        geo.semiMinorMetres = srs->GetSemiMinor();
        if (!(geo.semiMajorMetres > 0.0) || !(geo.semiMinorMetres > 0.0))
            throwBadInput(name + ": its coordinate system's ellipsoid has no size");
        const double degrees = srs->GetAngularUnits() * 180.0 / kPi;  // degrees per unit
        const double dx = stepX * degrees, dy = stepY * degrees;
        const double north = gt[3] * degrees, south = north - grid.height * dy;
        // A part in 1e9 of a degree for the rounding of the file's numbers.
        const double pastPole = 90.0 + dy / 2.0 + 1e-9;
        if (!(north <= pastPole) || !(south >= -pastPole)) {
            const double beyond = north > pastPole ? north : south;
            std::ostringstream message;
            message << name << ": its grid reaches " << std::abs(beyond) << " degrees "
                    << (north > pastPole ? "north" : "south")
                    << ", past the pole (a latitude/longitude grid lies from 90 S to 90 N)";
            throwBadInput(message.str());
        }
        if (!(grid.width * dx <= 360.0 + dx + 1e-9)) {
            std::ostringstream message;
            message << name << ": its grid spans " << grid.width * dx
                    << " degrees of longitude, more than the 360 round the Earth";
            throwBadInput(message.str());
        }
        const double centreLatitude = std::clamp((north + south) / 2.0, -90.0, 90.0);
        geo.sampleWidthMetres =
            dx * metresPerDegreeEast(geo.semiMajorMetres, geo.semiMinorMetres, centreLatitude);
        geo.sampleHeightMetres =
            dy * metresPerDegreeNorth(geo.semiMajorMetres, geo.semiMinorMetres, centreLatitude);
        geo.global = grid.width * dx >= 360.0 - dx / 2.0 && grid.height * dy >= 180.0 - dy / 2.0;
        // A grid at a pole has no width there; its samples' size is taken at the centre.
        if (!(geo.sampleWidthMetres > 0.0)) geo.sampleWidthMetres = geo.sampleHeightMetres;
    } else {
        const double metres = srs ? srs->GetLinearUnits() : 1.0;  // per grid unit
        geo.sampleWidthMetres = stepX * metres;
        geo.sampleHeightMetres = stepY * metres;
    }
    if (srs && srs->GetName()) geo.crs = srs->GetName();
    return geo;
}

}  // namespace

bool hasGeoTiffGrid(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char header[16] = {};
    if (!in.read(reinterpret_cast<char*>(header), 8)) return false;
    const bool little = header[0] == 'I' && header[1] == 'I';
    if (!little && !(header[0] == 'M' && header[1] == 'M')) return false;
    // The file's integers in its byte order.
    const auto number = [&](const unsigned char* bytes, int size) {
        std::uint64_t value = 0;
        for (int k = 0; k < size; ++k)
            value |= std::uint64_t(bytes[little ? k : size - 1 - k]) << (8 * k);
        return value;
    };
    const std::uint64_t version = number(header + 2, 2);
    if (version != 42 && version != 43) return false;
    const bool big = version == 43;  // BigTIFF: 8-byte offsets and counts, 20-byte entries
    if (big && !in.read(reinterpret_cast<char*>(header + 8), 8)) return false;
    const std::uint64_t directory = big ? number(header + 8, 8) : number(header + 4, 4);
    unsigned char count[8] = {};
    if (!in.seekg(static_cast<std::streamoff>(directory)) ||
        !in.read(reinterpret_cast<char*>(count), big ? 8 : 2))
        return false;
    const std::uint64_t entries = std::min<std::uint64_t>(number(count, big ? 8 : 2), 65535);
    const int entrySize = big ? 20 : 12;
    unsigned char entry[20];
    for (std::uint64_t k = 0; k < entries; ++k) {
        if (!in.read(reinterpret_cast<char*>(entry), entrySize)) return false;
        const std::uint64_t tag = number(entry, 2);
        // ModelPixelScale, ModelTiepoint, ModelTransformation (GeoTIFF 1.1, section 7).
        if (tag == 33550 || tag == 33922 || tag == 34264) return true;
    }
    return false;
}

bool isElevationModelFile(const std::filesystem::path& file) {
    std::string extension = lower(file.extension().string());
    return extension == ".hgt" ||
           ((extension == ".tif" || extension == ".tiff") && hasGeoTiffGrid(file));
}

namespace {

// The elevation model opened through GDAL (the caller's QuietGdal catching its messages),
// refused where it cannot be read; its geotransform in `gt`.
std::shared_ptr<GDALDataset> openDem(const std::filesystem::path& file, double gt[6]) {
    const std::string name = file.string();
    // Only the elevation formats' drivers: nothing else GDAL reads is tried on the file.
    const char* const drivers[] = {"GTiff", "SRTMHGT", nullptr};
    const std::shared_ptr<GDALDataset> dataset(
        GDALDataset::Open(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers),
        DatasetCloser{});
    if (!dataset) {
        std::string hint;
        if (lower(file.extension().string()) == ".hgt")
            hint =
                "; an SRTM tile is named for its corner, N45E006.hgt, and holds 1201 x 1201 "
                "or 3601 x 3601 samples";
        throwBadInput(name + ": cannot read the elevation model (" + QuietGdal::lastError() + ")" +
                      hint);
    }
    if (dataset->GetGeoTransform(gt) != CE_None)
        throwBadInput(name + ": the elevation model has no grid on the ground");
    return dataset;
}

}  // namespace

Georeference demGrid(const std::filesystem::path& file) {
    const QuietGdal quiet;
    double gt[6];
    const std::shared_ptr<GDALDataset> dataset = openDem(file, gt);
    const std::string name = file.string();
    return groundOf(name,
                    northUpGrid(name, gt, dataset->GetRasterXSize(), dataset->GetRasterYSize()),
                    dataset->GetSpatialRef());
}

DemRows demRows(const std::filesystem::path& file, const HeightMapLoadOptions& options,
                const std::function<void(long long done, long long total)>& firstPass) {
    const std::string name = file.string();
    const QuietGdal quiet;
    double gt[6];
    const std::shared_ptr<GDALDataset> dataset = openDem(file, gt);

    const int width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
    checkSize(name, width, height, options.maxSide, "a height map", options.maxSamples);
    const NorthUpGrid grid = northUpGrid(name, gt, width, height);
    const int bands = dataset->GetRasterCount();
    if (options.channel < 0 || options.channel >= bands) {
        throwBadInput(name + ": {map.load.channel} " + std::to_string(options.channel) +
                      " is out of range; the elevation model has " + std::to_string(bands) +
                      " band(s)");
    }
    GDALRasterBand* band = dataset->GetRasterBand(options.channel + 1);
    Georeference geo = groundOf(name, grid, dataset->GetSpatialRef());

    // How a stored value becomes metres, or nodata.
    struct Heights {
        bool hasNodata = false;
        double nodata = 0.0, scale = 1.0, offset = 0.0, unit = 1.0;
        bool isNodata(double raw) const {
            return hasNodata && (raw == nodata || (std::isnan(nodata) && std::isnan(raw)));
        }
        double metres(double raw) const { return (raw * scale + offset) * unit; }
    } heights;
    int hasNodata = 0, hasScale = 0, hasOffset = 0;
    heights.nodata = band->GetNoDataValue(&hasNodata);
    heights.hasNodata = hasNodata != 0;
    heights.scale = band->GetScale(&hasScale);
    heights.offset = band->GetOffset(&hasOffset);
    if (!hasScale) heights.scale = 1.0;
    if (!hasOffset) heights.offset = 0.0;
    heights.unit = verticalUnit(name, band->GetUnitType());

    // Lines y0 .. y1 - 1 of the file, read as double (the nodata test on the stored value;
    // integer heights up to 2^53 exact until they are metres), in blocks of about 4 M
    // samples handed to `use(firstLine, lineCount, samples)`: its rows as stored, or, where
    // `columns`, its columns y0 .. y1 - 1, each laid out as a row (GDAL's buffer spacing
    // transposes them as they are read).
    const auto readBlocks = [dataset, band, name, width, height](bool columns, int y0, int y1,
                                                                 const auto& use) {
        const QuietGdal quietHere;
        const int length = columns ? height : width;
        const int blockLines = std::max(1, (1 << 22) / length);
        std::vector<double> block(static_cast<std::size_t>(length) * std::min(blockLines, y1 - y0));
        for (int y = y0; y < y1; y += blockLines) {
            const int count = std::min(blockLines, y1 - y);
            const CPLErr read =
                columns ? band->RasterIO(GF_Read, y, 0, count, height, block.data(), count, height,
                                         GDT_Float64, sizeof(double) * height, sizeof(double))
                        : band->RasterIO(GF_Read, 0, y, width, count, block.data(), width, count,
                                         GDT_Float64, 0, 0);
            if (read != CE_None)
                throwBadInput(name + ": cannot read the samples (" + QuietGdal::lastError() + ")");
            use(y, count, block.data());
        }
    };

    // The first pass: the valid heights' range and the nodata samples.
    double lowest = std::numeric_limits<double>::infinity();
    double highest = -lowest;
    readBlocks(false, 0, height, [&](int y, int count, const double* block) {
        for (std::size_t k = 0; k < static_cast<std::size_t>(count) * width; ++k) {
            const double raw = block[k];
            if (heights.isNodata(raw)) {
                ++geo.nodataSamples;
                continue;
            }
            const double metres = heights.metres(raw);
            if (!std::isfinite(metres)) {
                std::ostringstream message;
                message << name << ": sample (" << k % width << ", " << y + k / width << ") is "
                        << raw << ", not a height (and not the file's nodata value)";
                throwBadInput(message.str());
            }
            lowest = std::min(lowest, metres);
            highest = std::max(highest, metres);
        }
        // Counted in the map's rows, which the rows' reads count too.
        if (firstPass)
            firstPass(static_cast<long long>(y + count) * grid.height / height, grid.height);
    });
    if (geo.nodataSamples == static_cast<std::size_t>(width) * height)
        throwBadInput(name + ": every sample is nodata");
    geo.lowestMetres = lowest;
    geo.highestMetres = highest;

    // North up, east to the right (NorthUpGrid): the map's rows are the file's rows or
    // columns, each line and the lines' order read in reverse where they run the other way.
    DemRows result;
    result.georeference = geo;
    const char* const wkt = dataset->GetProjectionRef();
    result.placement = {grid.geotransform, wkt ? wkt : ""};
    result.rows.width = grid.width;
    result.rows.height = grid.height;
    // Map rows y0 .. y1 - 1: [lowest, highest] metres -> [0, 1], worked in double and rounded
    // once to float; nodata -> 0, the lowest valid height. The result needs no clamp: for
    // lowest <= m <= highest, rounded subtraction and division are monotonic, so
    // 0 = fl(0 / range) <= fl(fl(m - lowest) / range) <= fl(range / range) = 1. A height
    // outside the first pass's range means the file changed since: refused, as a map that
    // changed under a build is.
    result.rows.read = [readBlocks, heights, name, grid, lowest, highest](int y0, int y1,
                                                                          float* out) {
        const int width = grid.width, height = grid.height;
        const bool flipRows = grid.flipRows, flipColumns = grid.flipColumns;
        const int f0 = flipRows ? height - y1 : y0, f1 = flipRows ? height - y0 : y1;
        const double range = highest - lowest;
        readBlocks(grid.transposed, f0, f1, [&](int y, int count, const double* block) {
            for (int r = 0; r < count; ++r) {
                const int row = flipRows ? height - 1 - (y + r) : y + r;
                float* to = out + static_cast<std::ptrdiff_t>(row - y0) * width;
                for (int x = 0; x < width; ++x) {
                    const double raw = block[static_cast<std::size_t>(r) * width + x];
                    float& sample = to[flipColumns ? width - 1 - x : x];
                    if (heights.isNodata(raw)) {
                        sample = 0.0f;
                        continue;
                    }
                    const double metres = heights.metres(raw);
                    if (!(metres >= lowest && metres <= highest))
                        throwBadInput(name + ": the elevation model changed while it was read");
                    sample = range == 0.0 ? 0.0f : static_cast<float>((metres - lowest) / range);
                }
            }
        });
    };
    return result;
}

HeightMapFile loadDem(const std::filesystem::path& file, const HeightMapLoadOptions& options) {
    DemRows dem = demRows(file, options);
    try {
        HeightMapFile result;
        result.map = HeightMap(dem.rows.width, dem.rows.height);
        dem.rows.read(0, dem.rows.height, result.map.samples.data());
        result.georeference = dem.georeference;
        result.placement = dem.placement;
        return result;
    } catch (const std::bad_alloc&) {
        throwRuntime(file.string() + ": not enough memory for its " +
                     std::to_string(dem.rows.width) + " x " + std::to_string(dem.rows.height) +
                     " samples");
    }
}

void writeDem(const std::filesystem::path& file, const HeightMap& map, const Georeference& geo,
              const GroundPlacement& placement) {
    const std::string name = file.string();
    const double lowest = geo.lowestMetres, range = geo.highestMetres - geo.lowestMetres;
    if (range == 0.0 &&
        std::any_of(map.samples.begin(), map.samples.end(), [](float h) { return h != 0.0f; })) {
        std::ostringstream message;
        message << name << ": the elevation model it came from is flat (every height " << lowest
                << " m), so the map's heights have no size in metres; save it as .exr";
        throwBadInput(message.str());
    }
    const QuietGdal quiet;
    // GDAL writes the GeoTIFF in memory; it goes to the file whole or not at all
    // (io/AtomicFile.h), as every output does.
    static std::atomic<unsigned> serial{0};
    const std::string memory = "/vsimem/microrelief-" + std::to_string(::getpid()) + "-" +
                               std::to_string(serial++) + ".tif";
    struct MemoryFile {
        std::string path;
        ~MemoryFile() { VSIUnlink(path.c_str()); }
    } const inMemory{memory};
    GDALDriver* const driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) throwRuntime(name + ": GDAL has no GeoTIFF writer");
    const char* const options[] = {"TILED=YES", "COMPRESS=DEFLATE", "PREDICTOR=3",
                                   "BIGTIFF=IF_SAFER", nullptr};
    std::unique_ptr<GDALDataset, DatasetCloser> dataset(driver->Create(
        memory.c_str(), map.width, map.height, 1, GDT_Float32, const_cast<char**>(options)));
    const auto failed = [&] {
        throwRuntime(name + ": cannot write the elevation model (" + QuietGdal::lastError() + ")");
    };
    if (!dataset) failed();
    std::array<double, 6> gt = placement.geotransform;
    if (dataset->SetGeoTransform(gt.data()) != CE_None) failed();
    if (!placement.projectionWkt.empty() &&
        dataset->SetProjection(placement.projectionWkt.c_str()) != CE_None)
        failed();
    GDALRasterBand* const band = dataset->GetRasterBand(1);
    band->SetUnitType("m");
    std::vector<float> row(static_cast<std::size_t>(map.width));
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x)
            row[x] = static_cast<float>(lowest + static_cast<double>(map.at(x, y)) * range);
        if (band->RasterIO(GF_Write, 0, y, map.width, 1, row.data(), map.width, 1, GDT_Float32, 0,
                           0) != CE_None)
            failed();
    }
    CPLErrorReset();
    dataset.reset();  // GDALClose: the file's last blocks and directory
    if (CPLGetLastErrorType() == CE_Failure) failed();
    vsi_l_offset length = 0;
    const GByte* const bytes = VSIGetMemFileBuffer(memory.c_str(), &length, FALSE);
    if (!bytes) failed();
    writeFileAtomically(file, std::string_view(reinterpret_cast<const char*>(bytes),
                                               static_cast<std::size_t>(length)));
}

}  // namespace microrelief
