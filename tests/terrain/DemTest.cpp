// Georeferenced elevation models (docs/terrain.md): read through GDAL as metres with their
// grid (DemFile.*, label cpu), and drawn by microrelief-render at their true proportions
// (DemRender.*, label cli: the AOV's world positions against the file's own metres).
// The DEMs are written here with GDAL's own writer. Where the io component is built
// without GDAL, only the fit and the refusal of a DEM file are built (CMake says so when it
// configures: "no GDAL, elevation models are not read").
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#if MICRORELIEF_WITH_GDAL
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#endif

#include "TestSupport.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Machine.h"
#include "microrelief/core/scene/Georeference.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/PyramidFile.h"

using namespace microrelief;

namespace {

// What a test DEM holds: a W x H band of `type` over a grid `gt` in the system `crs`
// (anything OGRSpatialReference::SetFromUserInput takes, "EPSG:32633"; empty: none).
struct DemSpec {
    int width = 40, height = 30;
    std::string crs = "EPSG:32633";  // WGS 84 / UTM zone 33N
    double gt[6] = {500000.0, 30.0, 0.0, 5000000.0, 0.0, -30.0};
    std::optional<double> nodata;
    std::string unit;
    double scale = 1.0, offset = 0.0;
    bool georeferenced = true;
    std::function<double(int, int)> value = [](int i, int j) { return 100.0 + 3 * i + 7 * j; };
};

#if MICRORELIEF_WITH_GDAL
void writeDem(const std::filesystem::path& file, const DemSpec& spec, GDALDataType type) {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    ASSERT_NE(driver, nullptr);
    GDALDataset* dataset = driver->Create(file.c_str(), spec.width, spec.height, 1, type, nullptr);
    ASSERT_NE(dataset, nullptr);
    if (spec.georeferenced) {
        double gt[6];
        std::copy(spec.gt, spec.gt + 6, gt);
        dataset->SetGeoTransform(gt);
        if (!spec.crs.empty()) {
            OGRSpatialReference srs;
            ASSERT_EQ(srs.SetFromUserInput(spec.crs.c_str()), OGRERR_NONE);
            dataset->SetSpatialRef(&srs);
        }
    }
    GDALRasterBand* band = dataset->GetRasterBand(1);
    if (spec.nodata) band->SetNoDataValue(*spec.nodata);
    if (!spec.unit.empty()) band->SetUnitType(spec.unit.c_str());
    if (spec.scale != 1.0) band->SetScale(spec.scale);
    if (spec.offset != 0.0) band->SetOffset(spec.offset);
    std::vector<double> samples(static_cast<std::size_t>(spec.width) * spec.height);
    for (int j = 0; j < spec.height; ++j)
        for (int i = 0; i < spec.width; ++i)
            samples[static_cast<std::size_t>(j) * spec.width + i] = spec.value(i, j);
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, spec.width, spec.height, samples.data(), spec.width,
                             spec.height, GDT_Float64, 0, 0),
              CE_None);
    GDALClose(dataset);
}

#endif  // MICRORELIEF_WITH_GDAL

std::string refusal(const std::filesystem::path& file, const HeightMapLoadOptions& options = {}) {
    try {
        loadHeightMapFile(file, options);
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        return e.what();
    }
    ADD_FAILURE() << file << " was read";
    return {};
}

#if MICRORELIEF_WITH_GDAL

TEST(DemFile, AProjectedGeoTiffIsReadAsMetresOverItsGrid) {
    test::ScratchDir dir;
    DemSpec spec;
    spec.nodata = -32768.0;
    const auto value = spec.value;
    spec.value = [&](int i, int j) {
        return (j == 5 && (i == 5 || i == 6)) ? -32768.0 : value(i, j);
    };
    writeDem(dir / "utm.tif", spec, GDT_Int16);

    const HeightMapFile dem = loadHeightMapFile(dir / "utm.tif");
    ASSERT_TRUE(dem.georeference);
    const Georeference& geo = *dem.georeference;
    EXPECT_EQ(geo.sampleWidthMetres, 30.0);
    EXPECT_EQ(geo.sampleHeightMetres, 30.0);
    EXPECT_EQ(geo.lowestMetres, 100.0);
    EXPECT_EQ(geo.highestMetres, 100.0 + 3 * 39 + 7 * 29);
    EXPECT_EQ(geo.nodataSamples, 2u);
    EXPECT_FALSE(geo.geographic);
    EXPECT_NE(geo.crs.find("UTM zone 33N"), std::string::npos) << geo.crs;
    ASSERT_EQ(dem.map.width, 40);
    ASSERT_EQ(dem.map.height, 30);
    const double range = geo.highestMetres - geo.lowestMetres;
    for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 40; ++i) {
            const bool hole = j == 5 && (i == 5 || i == 6);
            EXPECT_FLOAT_EQ(dem.map.at(i, j), hole ? 0.0f : float((value(i, j) - 100.0) / range))
                << i << ", " << j;
        }
    // loadHeightMap: the same samples, without the grid.
    EXPECT_EQ(loadHeightMap(dir / "utm.tif").samples, dem.map.samples);
}

// The map is north up and east to the right whatever way the file lays its grid on the
// ground, where its rows and columns run east-west and north-south: each of the eight (the
// turns by 0, 90, 180 and 270 degrees, each also mirrored; a transposed grid is a turned one
// mirrored) holds the same ground as the north-up twin and reads as the same map, sample for
// sample, with the same georeference, whole and by rows. Samples of 30 x 20 m on a 40 x 30
// grid: a turn that swapped the sides or the sample sizes is seen.
namespace {

struct GridLayout {
    const char* name;
    int columnEast, columnNorth;  // the file's column step: one sample east, west, north or south
    int rowEast, rowNorth;        // and its row step
};
const GridLayout kGridLayouts[] = {
    {"north up", 1, 0, 0, -1},
    {"south up (rows running north)", 1, 0, 0, 1},
    {"east to west", -1, 0, 0, -1},
    {"turned 180 degrees", -1, 0, 0, 1},
    {"transposed (columns running south, rows east)", 0, -1, 1, 0},
    {"turned 90 degrees clockwise (columns running south, rows west)", 0, -1, -1, 0},
    {"turned 90 degrees anticlockwise (columns running north, rows east)", 0, 1, 1, 0},
    {"transposed the other way (columns running north, rows west)", 0, 1, -1, 0},
};

// The north-up twin's ground: W x H samples of dx x dy metres from (x0, y0), the north-west
// corner; and the file of `layout` that holds it.
struct TwinGround {
    int width = 40, height = 30;
    double x0 = 500000.0, y0 = 5000000.0, dx = 30.0, dy = 20.0;
    double value(int i, int j) const { return 100.0 + i + 41.0 * j; }  // each sample its own
};
DemSpec laidOut(const TwinGround& ground, const GridLayout& layout) {
    DemSpec spec;
    const bool columnsEast = layout.columnEast != 0;
    spec.width = columnsEast ? ground.width : ground.height;
    spec.height = columnsEast ? ground.height : ground.width;
    const double gt[6] = {
        layout.columnEast < 0 || layout.rowEast < 0 ? ground.x0 + ground.width * ground.dx
                                                    : ground.x0,
        layout.columnEast * ground.dx,
        layout.rowEast * ground.dx,
        layout.columnNorth > 0 || layout.rowNorth > 0 ? ground.y0 - ground.height * ground.dy
                                                      : ground.y0,
        layout.columnNorth * ground.dy,
        layout.rowNorth * ground.dy};
    std::copy(gt, gt + 6, spec.gt);
    spec.value = [ground, gt](int c, int r) {
        // The sample's centre on the ground, and the twin's sample there.
        const double x = gt[0] + (c + 0.5) * gt[1] + (r + 0.5) * gt[2];
        const double y = gt[3] + (c + 0.5) * gt[4] + (r + 0.5) * gt[5];
        return ground.value(static_cast<int>(std::floor((x - ground.x0) / ground.dx)),
                            static_cast<int>(std::floor((ground.y0 - y) / ground.dy)));
    };
    return spec;
}

}  // namespace

TEST(DemFile, EveryGridAlongTheAxesIsTurnedNorthUpExactly) {
    test::ScratchDir dir;
    const TwinGround ground;
    DemSpec twin;
    twin.width = ground.width;
    twin.height = ground.height;
    const double gt[6] = {ground.x0, ground.dx, 0.0, ground.y0, 0.0, -ground.dy};
    std::copy(gt, gt + 6, twin.gt);
    twin.value = [ground](int i, int j) { return ground.value(i, j); };
    writeDem(dir / "twin.tif", twin, GDT_Float32);
    const HeightMapFile north = loadHeightMapFile(dir / "twin.tif");
    ASSERT_TRUE(north.georeference);
    ASSERT_EQ(north.georeference->sampleWidthMetres, 30.0);
    ASSERT_EQ(north.georeference->sampleHeightMetres, 20.0);
    ASSERT_FLOAT_EQ(north.map.at(1, 0), 1.0f / (39 + 41 * 29));  // east of the corner

    for (const GridLayout& layout : kGridLayouts) {
        SCOPED_TRACE(layout.name);
        const std::filesystem::path file = dir / (std::string(layout.name) + ".tif");
        writeDem(file, laidOut(ground, layout), GDT_Float32);
        const HeightMapFile dem = loadHeightMapFile(file);
        EXPECT_EQ(dem.map.width, north.map.width);
        EXPECT_EQ(dem.map.height, north.map.height);
        EXPECT_EQ(dem.map.samples, north.map.samples);
        EXPECT_EQ(dem.georeference, north.georeference);
        // By rows, in bands of 7 (a pyramid file's build reads them so), and from the header.
        const MapFileRows rows = heightMapFileRows(file, {});
        ASSERT_EQ(rows.rows.width, north.map.width);
        ASSERT_EQ(rows.rows.height, north.map.height);
        std::vector<float> read(north.map.samples.size(), -1.0f);
        for (int y0 = 0; y0 < rows.rows.height; y0 += 7)
            rows.rows.read(y0, std::min(rows.rows.height, y0 + 7),
                           read.data() + static_cast<std::ptrdiff_t>(y0) * rows.rows.width);
        EXPECT_EQ(read, north.map.samples);
        const std::optional<Georeference> grid = readMapGrid(file);
        ASSERT_TRUE(grid);
        EXPECT_EQ(grid->sampleWidthMetres, 30.0);
        EXPECT_EQ(grid->sampleHeightMetres, 20.0);
    }
}

// A DEM's map saved (the viewer's --save-map FILE.tif) is a GeoTIFF of metres that lies where
// the map came from: the north-up geotransform and the coordinate system of the file it was
// read from (here one turned 90 degrees), one Float32 band in metres; read back, the same
// map and georeference. Edited heights above 1 stand at their metres. Seen red: before,
// only .png and .exr were written, with no grid.
TEST(DemFile, ASavedElevationModelLiesWhereItCameFrom) {
    test::ScratchDir dir;
    const TwinGround ground;
    DemSpec turned = laidOut(ground, kGridLayouts[5]);
    writeDem(dir / "turned.tif", turned, GDT_Float32);
    HeightMapFile dem = loadHeightMapFile(dir / "turned.tif");
    ASSERT_TRUE(dem.georeference);
    ASSERT_TRUE(dem.placement);
    EXPECT_EQ(dem.placement->geotransform,
              (std::array<double, 6>{ground.x0, ground.dx, 0.0, ground.y0, 0.0, -ground.dy}));
    saveElevationModel(dir / "saved.tif", dem.map, *dem.georeference, *dem.placement);

    GDALAllRegister();
    GDALDataset* saved = GDALDataset::Open((dir / "saved.tif").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(saved, nullptr);
    double gt[6];
    ASSERT_EQ(saved->GetGeoTransform(gt), CE_None);
    EXPECT_EQ(std::vector<double>(gt, gt + 6),
              (std::vector<double>{ground.x0, ground.dx, 0.0, ground.y0, 0.0, -ground.dy}));
    OGRSpatialReference utm;
    ASSERT_EQ(utm.SetFromUserInput("EPSG:32633"), OGRERR_NONE);
    ASSERT_NE(saved->GetSpatialRef(), nullptr);
    EXPECT_TRUE(saved->GetSpatialRef()->IsSame(&utm));
    EXPECT_EQ(saved->GetRasterXSize(), ground.width);
    GDALRasterBand* band = saved->GetRasterBand(1);
    EXPECT_EQ(band->GetRasterDataType(), GDT_Float32);
    EXPECT_STREQ(band->GetUnitType(), "m");
    float corner[2] = {};
    ASSERT_EQ(band->RasterIO(GF_Read, 0, 0, 2, 1, corner, 2, 1, GDT_Float32, 0, 0), CE_None);
    EXPECT_NEAR(corner[0], ground.value(0, 0), 1e-3);  // the north-west corner, in metres
    EXPECT_NEAR(corner[1], ground.value(1, 0), 1e-3);  // east of it
    GDALClose(saved);

    const HeightMapFile again = loadHeightMapFile(dir / "saved.tif");
    EXPECT_EQ(again.placement, dem.placement);
    ASSERT_TRUE(again.georeference);
    EXPECT_EQ(again.georeference->sampleWidthMetres, 30.0);
    EXPECT_EQ(again.georeference->sampleHeightMetres, 20.0);
    EXPECT_EQ(again.georeference->lowestMetres, dem.georeference->lowestMetres);
    EXPECT_EQ(again.georeference->highestMetres, dem.georeference->highestMetres);
    EXPECT_EQ(again.georeference->crs, dem.georeference->crs);
    ASSERT_EQ(again.map.samples.size(), dem.map.samples.size());
    for (std::size_t k = 0; k < dem.map.samples.size(); ++k)
        ASSERT_NEAR(again.map.samples[k], dem.map.samples[k], 1e-6) << k;

    // Raised past the highest sample: 1.5 of the range above the lowest.
    dem.map.at(3, 4) = 1.5f;
    saveElevationModel(dir / "raised.tif", dem.map, *dem.georeference, *dem.placement);
    const double range = dem.georeference->highestMetres - dem.georeference->lowestMetres;
    EXPECT_NEAR(loadHeightMapFile(dir / "raised.tif").georeference->highestMetres,
                dem.georeference->lowestMetres + 1.5 * range, 1e-3);

    // A flat DEM's map has no metres for heights other than 0: refused, nothing written.
    Georeference flat = *dem.georeference;
    flat.highestMetres = flat.lowestMetres;
    try {
        saveElevationModel(dir / "flat.tif", dem.map, flat, *dem.placement);
        ADD_FAILURE() << "a flat DEM's edited map was saved";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("flat.tif: the elevation model it came from is flat"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "flat.tif"));
}

// A grid turned by another angle, or sheared, cannot be turned north up sample for sample:
// refused in one line that says how it lies (rather than drawn in its own orientation).
// Terms of a part in a million of a sample over the whole map are a grid along the axes.
TEST(DemFile, AGridTurnedByAnotherAngleOrShearedIsRefused) {
    test::ScratchDir dir;
    const double eighth = std::atan(1.0);  // of a turn: 45 degrees
    const double c = 30.0 * std::cos(eighth), s = 30.0 * std::sin(eighth);
    DemSpec turned;
    const double gt45[6] = {500000.0, c, s, 5000000.0, s, -c};  // turned 45 degrees
    std::copy(gt45, gt45 + 6, turned.gt);
    writeDem(dir / "turned.tif", turned, GDT_Int16);
    std::string message = refusal(dir / "turned.tif");
    EXPECT_NE(message.find("turned.tif: its grid is turned 45 degrees"), std::string::npos)
        << message;
    EXPECT_NE(message.find("gdalwarp"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;

    DemSpec sheared;
    const double gtShear[6] = {500000.0, 30.0, 10.0, 5000000.0, 0.0, -30.0};
    std::copy(gtShear, gtShear + 6, sheared.gt);
    writeDem(dir / "sheared.tif", sheared, GDT_Int16);
    message = refusal(dir / "sheared.tif");
    EXPECT_NE(message.find("sheared.tif: its grid is sheared"), std::string::npos) << message;
    // The header alone refuses it too (a pyramid file's build asks it first).
    try {
        readMapGrid(dir / "sheared.tif");
        ADD_FAILURE() << "a sheared grid's header was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sheared"), std::string::npos) << e.what();
    }

    DemSpec nearly;  // 1e-9 of a sample over the map: along the axes
    nearly.gt[2] = 30.0 * 1e-9 / nearly.height;
    writeDem(dir / "nearly.tif", nearly, GDT_Int16);
    writeDem(dir / "straight.tif", DemSpec{}, GDT_Int16);
    EXPECT_EQ(loadHeightMapFile(dir / "nearly.tif").map.samples,
              loadHeightMapFile(dir / "straight.tif").map.samples);
}

// A latitude/longitude grid lies between the poles and spans no more than the globe: one
// that reaches past a pole, or wraps round more than 360 degrees, is no grid on the Earth.
// A grid whose edges lie half a sample past the poles and the date line (samples centred on
// them, as ETOPO's "grid-registered" grids are) is one, and covers the globe.
TEST(DemFile, ALatitudeLongitudeGridPastThePolesIsRefused) {
    test::ScratchDir dir;
    const auto geographic = [](int width, int height, std::initializer_list<double> gt) {
        DemSpec spec;
        spec.width = width;
        spec.height = height;
        spec.crs = "EPSG:4326";
        std::copy(gt.begin(), gt.end(), spec.gt);
        return spec;
    };
    writeDem(dir / "north.tif", geographic(10, 10, {10.0, 1.0, 0.0, 95.0, 0.0, -1.0}),
             GDT_Int16);  // 95 N to 85 N: its centre is on the Earth, its top is not
    std::string message = refusal(dir / "north.tif");
    EXPECT_NE(message.find("north.tif: its grid reaches 95 degrees north, past the pole"),
              std::string::npos)
        << message;
    writeDem(dir / "south.tif", geographic(10, 20, {10.0, 1.0, 0.0, -75.0, 0.0, -1.0}),
             GDT_Int16);  // 75 S to 95 S
    message = refusal(dir / "south.tif");
    EXPECT_NE(message.find("south.tif: its grid reaches 95 degrees south, past the pole"),
              std::string::npos)
        << message;
    writeDem(dir / "south-up.tif", geographic(10, 20, {10.0, 1.0, 0.0, -95.0, 0.0, 1.0}),
             GDT_Int16);  // rows running north from 95 S
    EXPECT_NE(refusal(dir / "south-up.tif").find("95 degrees south"), std::string::npos);
    writeDem(dir / "wraps.tif", geographic(400, 10, {-180.0, 1.0, 0.0, 10.0, 0.0, -1.0}),
             GDT_Int16);
    message = refusal(dir / "wraps.tif");
    EXPECT_NE(message.find("wraps.tif: its grid spans 400 degrees of longitude"), std::string::npos)
        << message;

    writeDem(dir / "registered.tif", geographic(361, 181, {-180.5, 1.0, 0.0, 90.5, 0.0, -1.0}),
             GDT_Int16);
    const HeightMapFile globe = loadHeightMapFile(dir / "registered.tif");
    ASSERT_TRUE(globe.georeference);
    EXPECT_TRUE(globe.georeference->global);
}

// Heights far from zero (metres from the Earth's centre) keep their detail: the map of
// 6 371 000 m + h is the map of h.
TEST(DemFile, ALargeOffsetCostsNoPrecision) {
    test::ScratchDir dir;
    DemSpec spec;
    spec.value = [](int i, int j) { return 0.01 * ((i * 7 + j * 13) % 101); };
    writeDem(dir / "low.tif", spec, GDT_Float64);
    const auto value = spec.value;
    spec.value = [&](int i, int j) { return 6371000.0 + value(i, j); };
    writeDem(dir / "high.tif", spec, GDT_Float64);
    const HeightMap low = loadHeightMapFile(dir / "low.tif").map;
    const HeightMap high = loadHeightMapFile(dir / "high.tif").map;
    for (std::size_t k = 0; k < low.samples.size(); ++k)
        ASSERT_NEAR(high.samples[k], low.samples[k], 1e-6) << k;
}

TEST(DemFile, HeightsInFeetWithAScaleAndOffsetBecomeMetres) {
    test::ScratchDir dir;
    DemSpec spec;
    spec.unit = "ft";
    spec.scale = 0.5;
    spec.offset = 10.0;
    spec.value = [](int i, int j) { return double(i + j); };  // raw 0 .. 68
    writeDem(dir / "feet.tif", spec, GDT_Float32);
    const HeightMapFile dem = loadHeightMapFile(dir / "feet.tif");
    ASSERT_TRUE(dem.georeference);
    EXPECT_DOUBLE_EQ(dem.georeference->lowestMetres, 10.0 * 0.3048);
    EXPECT_DOUBLE_EQ(dem.georeference->highestMetres, (68 * 0.5 + 10.0) * 0.3048);

    spec.unit = "furlong";
    writeDem(dir / "furlong.tif", spec, GDT_Float32);
    EXPECT_NE(refusal(dir / "furlong.tif").find("'furlong'"), std::string::npos);
}

// Metres per degree on WGS 84 at 45 degrees north, as published (for example in the
// NGA's "Length of a degree" tables): 78 846.8 m east, 111 131.7 m north.
TEST(DemFile, ALatitudeLongitudeGridMeasuresItsSamplesAtItsCentre) {
    test::ScratchDir dir;
    DemSpec spec;
    spec.width = spec.height = 100;
    spec.crs = "EPSG:4326";
    const double gt[6] = {10.0, 0.001, 0.0, 45.05, 0.0, -0.001};  // centre at 45 N
    std::copy(gt, gt + 6, spec.gt);
    writeDem(dir / "geo.tif", spec, GDT_Int16);
    const HeightMapFile dem = loadHeightMapFile(dir / "geo.tif");
    ASSERT_TRUE(dem.georeference);
    EXPECT_TRUE(dem.georeference->geographic);
    EXPECT_FALSE(dem.georeference->global);
    EXPECT_NEAR(dem.georeference->sampleWidthMetres, 78.8468, 0.001);
    EXPECT_NEAR(dem.georeference->sampleHeightMetres, 111.1317, 0.001);
    EXPECT_EQ(dem.georeference->semiMajorMetres, 6378137.0);
}

// A global latitude/longitude grid of 5-degree samples, 72 x 36, in metres from -4000 to
// 4900 (Int16).
DemSpec globeSpec() {
    DemSpec spec;
    spec.width = 72;
    spec.height = 36;
    spec.crs = "EPSG:4326";
    const double gt[6] = {-180.0, 5.0, 0.0, 90.0, 0.0, -5.0};
    std::copy(gt, gt + 6, spec.gt);
    spec.value = [](int i, int j) { return -4000.0 + 100.0 * ((i * 7 + j * 3) % 90); };
    return spec;
}

TEST(DemFile, AGlobalGridGoesOnTheEllipsoidOfItsAxes) {
    test::ScratchDir dir;
    writeDem(dir / "globe.tif", globeSpec(), GDT_Int16);
    const HeightMapFile dem = loadHeightMapFile(dir / "globe.tif");
    ASSERT_TRUE(dem.georeference);
    EXPECT_TRUE(dem.georeference->global);
    EXPECT_NEAR(dem.georeference->semiMinorMetres, 6356752.314, 0.001);

    ReliefDesc relief;
    fitToGeoreference(relief, 72, 36, *dem.georeference, {});
    ASSERT_EQ(relief.base.kind, BaseKind::Ellipsoid);
    EXPECT_EQ(relief.base.radii, glm::dvec3(0.5, 0.5 * 6356752.314245179 / 6378137.0, 0.5));
    EXPECT_FLOAT_EQ(relief.heightScale, float(8900.0 / 6378137.0));
    // A base given is kept; the height scale then measures the map's width round it.
    ReliefDesc plane;
    fitToGeoreference(plane, 72, 36, *dem.georeference, {.exaggeration = 10, .keepBase = true});
    EXPECT_EQ(plane.base.kind, BaseKind::Plane);

    // The header alone says as much of the base (what a pyramid file is built for before
    // the map is read); an image has no grid.
    const std::optional<Georeference> grid = readMapGrid(dir / "globe.tif");
    ASSERT_TRUE(grid);
    EXPECT_TRUE(grid->global);
    EXPECT_EQ(fittedBase(BaseShape{}, *grid, {}), relief.base);
    EXPECT_EQ(fittedBase(BaseShape{}, *grid, {.keepBase = true}).kind, BaseKind::Plane);
    test::writeMap(dir / "image.png", HeightMap(4, 4, 0.5f), PixelType::UInt16);
    EXPECT_FALSE(readMapGrid(dir / "image.png"));
}

TEST(DemFile, WhatIsNotAnElevationModelIsRefusedOrReadAsAnImage) {
    test::ScratchDir dir;
    DemSpec spec;
    spec.nodata = 7.0;
    spec.value = [](int, int) { return 7.0; };
    writeDem(dir / "holes.tif", spec, GDT_Int16);
    EXPECT_NE(refusal(dir / "holes.tif").find("every sample is nodata"), std::string::npos);

    spec = DemSpec{};
    spec.width = 200;
    writeDem(dir / "wide.tif", spec, GDT_Int16);
    EXPECT_NE(refusal(dir / "wide.tif", {.maxSide = 100}).find("200 x 30 is larger than"),
              std::string::npos);
    EXPECT_NE(refusal(dir / "wide.tif", {.channel = 1}).find("1 band(s)"), std::string::npos);

    test::writeBytes(dir / "N45E006.hgt", std::vector<std::uint8_t>(1000, 7));
    EXPECT_NE(refusal(dir / "N45E006.hgt").find("N45E006.hgt: cannot read the elevation model"),
              std::string::npos);
    std::filesystem::create_directory(dir / "folder.tif");
    EXPECT_NE(refusal(dir / "folder.tif").find("is a directory"), std::string::npos);

    // A TIFF with no grid on the ground is an image, as before.
    spec = DemSpec{};
    spec.georeferenced = false;
    spec.value = [](int i, int) { return 1000.0 * i; };
    writeDem(dir / "image.tif", spec, GDT_UInt16);
    const HeightMapFile image = loadHeightMapFile(dir / "image.tif");
    EXPECT_FALSE(image.georeference);
    EXPECT_FLOAT_EQ(image.map.at(39, 0), 39000.0f / 65535.0f);

    // The rows of a TIFF with no grid are an image's, with no georeference.
    const MapFileRows imageRows = heightMapFileRows(dir / "image.tif", {});
    EXPECT_EQ(imageRows.rows.width, 40);
    EXPECT_FALSE(imageRows.georeference);
}

// A DEM larger than memory is drawn from its pyramid file (docs/terrain.md): its rows, read
// a block at a time, are the samples loadHeightMapFile reads, bit for bit, whatever bands
// they are read in (a south-up grid in feet with holes, a latitude/longitude one), and its
// pyramid file keeps the georeference the proportions come from.
TEST(DemFile, ItsRowsAndPyramidFileAreWhatLoadingItWholeGives) {
    test::ScratchDir dir;
    DemSpec southUp;
    southUp.width = 300;  // pages of 256: two across
    southUp.height = 70;
    southUp.gt[3] = 5000000.0 - 30.0 * southUp.height;
    southUp.gt[5] = 30.0;
    southUp.nodata = -9999.0;
    southUp.unit = "ft";
    southUp.value = [](int i, int j) {
        return (i + j) % 37 == 0 ? -9999.0 : 1200.5 + 0.25 * ((i * 13 + j * 29) % 211);
    };
    writeDem(dir / "south-up.tif", southUp, GDT_Float32);
    DemSpec geographic;
    geographic.width = geographic.height = 100;
    geographic.crs = "EPSG:4326";
    const double gt[6] = {10.0, 0.001, 0.0, 45.05, 0.0, -0.001};
    std::copy(gt, gt + 6, geographic.gt);
    writeDem(dir / "geo.tif", geographic, GDT_Int16);

    for (const char* name : {"south-up.tif", "geo.tif"}) {
        SCOPED_TRACE(name);
        const std::filesystem::path file = dir / name;
        const HeightMapFile whole = loadHeightMapFile(file);
        ASSERT_TRUE(whole.georeference);
        const MapFileRows rows = heightMapFileRows(file, {});
        EXPECT_EQ(rows.georeference, whole.georeference);
        ASSERT_EQ(rows.rows.width, whole.map.width);
        ASSERT_EQ(rows.rows.height, whole.map.height);
        std::vector<float> read(whole.map.samples.size(), -1.0f);
        for (int y0 = 0; y0 < rows.rows.height; y0 += 23) {
            const int y1 = std::min(rows.rows.height, y0 + 23);
            rows.rows.read(y0, y1, read.data() + static_cast<std::ptrdiff_t>(y0) * rows.rows.width);
        }
        EXPECT_EQ(read, whole.map.samples);

        // The build's progress counts the DEM's first pass (its range) and the stream's two
        // as one: from the start, in order, to the end.
        std::vector<std::pair<long long, long long>> heard;
        const auto progress = [&](long long done, long long total) {
            heard.emplace_back(done, total);
        };
        bool built = false;
        const auto pages = openOrBuildPyramidFile(file, dir / "cache", {}, false, progress, &built);
        EXPECT_TRUE(built);
        ASSERT_FALSE(heard.empty());
        EXPECT_EQ(heard.front().second, 3LL * whole.map.height);
        EXPECT_LE(heard.front().first, whole.map.height);
        EXPECT_EQ(heard.back().first, heard.back().second);
        for (std::size_t k = 1; k < heard.size(); ++k) {
            EXPECT_GE(heard[k].first, heard[k - 1].first) << k;
            EXPECT_EQ(heard[k].second, heard[0].second) << k;
        }
        EXPECT_EQ(pages->georeference(), whole.georeference);
        std::vector<float> level0(whole.map.samples.size());
        pages->read(0, {0, 0, whole.map.width, whole.map.height}, level0.data());
        EXPECT_EQ(level0, whole.map.samples);
        // Opened again from the cache: the georeference read back from its header.
        const auto again = openOrBuildPyramidFile(file, dir / "cache", {}, false, {}, &built);
        EXPECT_FALSE(built);
        EXPECT_EQ(again->georeference(), whole.georeference);
    }
}

#else

TEST(DemFile, WithoutGdalAnElevationFormatIsRefusedSayingSo) {
    EXPECT_FALSE(readsGeoreferencedMaps());
    test::ScratchDir dir;
    test::writeBytes(dir / "N45E006.hgt", std::vector<std::uint8_t>(1000, 7));
    EXPECT_NE(refusal(dir / "N45E006.hgt").find("GDAL"), std::string::npos);
}

#endif  // MICRORELIEF_WITH_GDAL

// The fit alone (core): the plane's height scale and its stretch for samples that are not
// square on the ground.
TEST(Georeference, ThePlaneTakesTheGroundsProportions) {
    Georeference geo;
    geo.sampleWidthMetres = 30.0;
    geo.sampleHeightMetres = 60.0;
    geo.lowestMetres = 100.0;
    geo.highestMetres = 420.0;
    ReliefDesc relief;
    fitToGeoreference(relief, 64, 32, geo, {.exaggeration = 2.0});
    // Ground 1920 x 1920 m: one world unit each way; 320 m is 1/6 of it, doubled.
    EXPECT_FLOAT_EQ(relief.heightScale, float(2.0 * 320.0 / 1920.0));
    const glm::dvec3 corner = relief.model.pointToWorld({0.5, 0.0, 0.25});  // the plane's corner
    EXPECT_DOUBLE_EQ(corner.x, 0.5);
    EXPECT_DOUBLE_EQ(corner.z, 0.5);
    // Tiled 2 x 1, the ground is 3840 x 1920 m: the longer side's unit is 3840 m, and the
    // samples, 30 x 60 m, stand 2 : 1 as the tiled map's 128 x 32 would not.
    ReliefDesc tiled;
    tiled.tiles = {2, 1};
    fitToGeoreference(tiled, 64, 32, geo, {});
    EXPECT_FLOAT_EQ(tiled.heightScale, float(320.0 / 3840.0));
    EXPECT_DOUBLE_EQ(tiled.model.pointToWorld({0.5, 0.0, 0.125}).z, 0.25);
    ReliefDesc kept;
    kept.heightScale = 0.3f;
    fitToGeoreference(kept, 64, 32, geo, {.keepHeightScale = true, .keepModel = true});
    EXPECT_EQ(kept.heightScale, 0.3f);
    EXPECT_TRUE(kept.model.isIdentity());
}

#if MICRORELIEF_WITH_GDAL

// --- microrelief-render over a DEM, label cli ---

using test::Aov;
using test::readAov;

class DemRender : public ::testing::Test {
protected:
    test::RunResult render(const std::string& args) {
        return test::runCommand(std::string(MICRORELIEF_RENDER_EXE) +
                                    " --backend auto --size 160x160 --eye 0,2.2,0.0001 "
                                    "--target 0,0,0 --up 0,0,-1 --fovy 40 " +
                                    args,
                                dir.path());
    }
    test::ScratchDir dir;
};

// A 64 x 32 DEM of 30 m samples, heights 100 m to 420 m, seen from above: every hit on its
// top lies where the file's own metres put it, one world unit being the 1920 m of its
// longer side: y = (bilinear metres at (x, z) - 100) / 1920 (times the exaggeration).
TEST_F(DemRender, ATerrainStandsAtItsTrueProportions) {
    DemSpec spec;
    spec.width = 64;
    spec.height = 32;
    spec.value = [](int i, int j) {
        return 100.0 + 320.0 * (0.5 + 0.5 * std::sin(i * 0.3) * std::cos(j * 0.4));
    };
    writeDem(dir / "dem.tif", spec, GDT_Float32);
    // The file's metres, bilinear between sample centres, clamped at the edges.
    const auto metres = [&](double x, double z, double zHalf) {
        const double u = (x + 0.5) * 64.0 - 0.5, v = (z + zHalf) / (2 * zHalf) * 32.0 - 0.5;
        const auto sample = [&](int i, int j) {
            return double(float(spec.value(std::clamp(i, 0, 63), std::clamp(j, 0, 31))));
        };
        const int i = int(std::floor(u)), j = int(std::floor(v));
        const double fu = u - i, fv = v - j;
        return (1 - fu) * (1 - fv) * sample(i, j) + fu * (1 - fv) * sample(i + 1, j) +
               (1 - fu) * fv * sample(i, j + 1) + fu * fv * sample(i + 1, j + 1);
    };
    struct Case {
        std::string flags;
        double exaggeration, zHalf;
        int sampleHeight;
    };
    for (const Case& c : {Case{"", 1.0, 0.25, 30}, Case{"--exaggeration 3", 3.0, 0.25, 30},
                          Case{"", 1.0, 0.5, 60}}) {
        SCOPED_TRACE(c.flags + " samples 30 x " + std::to_string(c.sampleHeight) + " m");
        spec.gt[5] = -c.sampleHeight;
        writeDem(dir / "dem.tif", spec, GDT_Float32);
        const HeightMapFile dem = loadHeightMapFile(dir / "dem.tif");
        ASSERT_TRUE(dem.georeference);
        const test::RunResult r =
            render("--height " + (dir / "dem.tif").string() + " " + c.flags + " --out " +
                   (dir / "dem.png").string() + " --aov " + (dir / "dem.exr").string());
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("true proportions"), std::string::npos) << r.out;
        const Aov aov = readAov(dir / "dem.exr");
        ASSERT_EQ(aov.width, 160);
        int tops = 0;
        double worst = 0.0, zMin = 1.0, zMax = -1.0;
        for (int y = 0; y < aov.height; ++y)
            for (int x = 0; x < aov.width; ++x) {
                const float* p = aov.at(x, y);
                if (p[3] == 0.0f) continue;
                zMin = std::min(zMin, double(p[2]));
                zMax = std::max(zMax, double(p[2]));
                if (std::abs(p[0]) > 0.49 || std::abs(p[2]) > c.zHalf - 0.01) continue;  // walls
                ++tops;
                const double expected =
                    (metres(p[0], p[2], c.zHalf) - dem.georeference->lowestMetres) / 1920.0 *
                    c.exaggeration;
                worst = std::max(worst, std::abs(p[1] - expected));
            }
        EXPECT_GT(tops, 160 * 160 / 8);
        // The hit's height against the file's at the hit's own (x, z): float positions, and
        // a slope of at most 320 m * 0.3 / 30 m per metre (times 3) between them: 1e-4.
        EXPECT_LT(worst, 1e-4);
        EXPECT_NEAR(zMin, -c.zHalf, 0.01);
        EXPECT_NEAR(zMax, c.zHalf, 0.01);

        // A camera path fits each frame's scene over the map the same way: a turntable's
        // first frame is the single view, pixel for pixel (the files' headers hold the time).
        const test::RunResult path = render(
            "-q --turntable 2 --height " + (dir / "dem.tif").string() + " " + c.flags + " --out " +
            (dir / "t{frame}.png").string() + " --aov " + (dir / "t{frame}.exr").string());
        ASSERT_EQ(path.status, 0) << path.err;
        EXPECT_EQ(readAov(dir / "t0.exr").pixels, aov.pixels);

        // Drawn from its pyramid file (a DEM larger than memory), through pages: the file
        // keeps the georeference, so the proportions and every hit are the same.
        const test::RunResult paged =
            render("--height " + (dir / "dem.tif").string() + " " + c.flags + " --pyramid-cache " +
                   (dir / "cache").string() + " --out " + (dir / "paged.png").string() + " --aov " +
                   (dir / "paged.exr").string());
        ASSERT_EQ(paged.status, 0) << paged.err;
        EXPECT_NE(paged.out.find("true proportions"), std::string::npos) << paged.out;
        EXPECT_NE(paged.out.find(", paged: "), std::string::npos) << paged.out;
        EXPECT_EQ(readAov(dir / "paged.exr").pixels, aov.pixels);
        // And a camera path from it: the georeference comes with the file there too.
        const test::RunResult pagedPath =
            render("-q --turntable 2 --height " + (dir / "dem.tif").string() + " " + c.flags +
                   " --pyramid-cache " + (dir / "cache").string() + " --out " +
                   (dir / "p{frame}.png").string() + " --aov " + (dir / "p{frame}.exr").string());
        ASSERT_EQ(pagedPath.status, 0) << pagedPath.err;
        EXPECT_EQ(readAov(dir / "p0.exr").pixels, aov.pixels);
    }
}

// A grid turned 90 degrees, or transposed, is drawn as its north-up twin: every hit where
// the twin's is (the AOV's world positions, float for float), whole and from its pyramid
// file. Seen red drawn turned and mirrored, at another size.
TEST_F(DemRender, AGridTurnedOrTransposedIsDrawnAsItsNorthUpTwin) {
    const TwinGround ground;
    writeDem(dir / "twin.tif", laidOut(ground, kGridLayouts[0]), GDT_Float32);
    const std::string view = " --out " + (dir / "x.png").string() + " --aov ";
    const test::RunResult twin =
        render("-q --height " + (dir / "twin.tif").string() + view + (dir / "twin.exr").string());
    ASSERT_EQ(twin.status, 0) << twin.err;
    const Aov expected = readAov(dir / "twin.exr");
    // Turned 90 degrees, whole and from its pyramid file; transposed, whole.
    const std::string pyramid = " --pyramid-cache " + (dir / "cache").string();
    for (const auto& [layout, cache] :
         {std::pair{kGridLayouts[5], std::string()}, std::pair{kGridLayouts[5], pyramid},
          std::pair{kGridLayouts[4], std::string()}}) {
        SCOPED_TRACE(std::string(layout.name) + cache);
        writeDem(dir / "turned.tif", laidOut(ground, layout), GDT_Float32);
        const test::RunResult r = render("-q --height " + (dir / "turned.tif").string() + cache +
                                         view + (dir / "turned.exr").string());
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_EQ(readAov(dir / "turned.exr").pixels, expected.pixels);
    }
}

// A map is admitted against the memory available now, not the machine's total (core/
// Machine.h; the variable stands for a machine with 512 MiB available): an 8000 x 8000 DEM,
// about 1 GiB to draw, is refused from its header in one line that says what was
// available. (The file is sparse: a few KiB on disk. Seen red: drawn, exit 0, as a 38000 x
// 38000 one was with 20 GiB available of this machine's 23.5, in two minutes.)
TEST_F(DemRender, AMapIsAdmittedAgainstTheMemoryAvailable) {
    GDALAllRegister();
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    ASSERT_NE(driver, nullptr);
    const char* const options[] = {"TILED=YES", "SPARSE_OK=TRUE", nullptr};
    const std::filesystem::path file = dir / "large.tif";
    GDALDataset* dataset =
        driver->Create(file.c_str(), 8000, 8000, 1, GDT_Int16, const_cast<char**>(options));
    ASSERT_NE(dataset, nullptr);
    double gt[6] = {500000.0, 30.0, 0.0, 5000000.0, 0.0, -30.0};
    dataset->SetGeoTransform(gt);
    GDALClose(dataset);
    ASSERT_LT(std::filesystem::file_size(file), 1u << 20);

    const test::RunResult r = test::runCommand(
        std::string(kAvailableMemoryVariable) + "=512 " + MICRORELIEF_RENDER_EXE +
            " --size 32x32 --height " + file.string() + " --out " + (dir / "x.png").string(),
        dir.path());
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_NE(r.err.find("large.tif: 8000 x 8000 samples need about 1 GiB of memory to draw, "
                         "more than the 0.5 GiB available now"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// A global latitude/longitude grid goes on the ellipsoid without --base; drawn from its
// pyramid file, which must be built for that base (it wraps round in u), it is the loaded
// map's picture, hit for hit, alone and along a camera path. Seen red: the file built for
// the plane the command line names ("its pyramid was built for the plane").
TEST_F(DemRender, AGlobalGridIsDrawnOnItsEllipsoidFromItsPyramidFile) {
    writeDem(dir / "globe.tif", globeSpec(), GDT_Int16);
    const std::string view = "--height " + (dir / "globe.tif").string() + " --exaggeration 40 ";
    const std::string cache = " --pyramid-cache " + (dir / "cache").string();
    const test::RunResult loaded =
        render(view + "--out " + (dir / "a.png").string() + " --aov " + (dir / "a.exr").string());
    ASSERT_EQ(loaded.status, 0) << loaded.err;
    EXPECT_NE(loaded.out.find("on the ellipsoid"), std::string::npos) << loaded.out;
    const test::RunResult paged = render(view + cache + " --out " + (dir / "b.png").string() +
                                         " --aov " + (dir / "b.exr").string());
    ASSERT_EQ(paged.status, 0) << paged.err;
    EXPECT_NE(paged.out.find(", paged: "), std::string::npos) << paged.out;
    const Aov a = readAov(dir / "a.exr");
    EXPECT_GT(std::count_if(a.pixels.begin(), a.pixels.end(), [](float v) { return v != 0.0f; }),
              1000);
    EXPECT_EQ(readAov(dir / "b.exr").pixels, a.pixels);
    const std::string turntable =
        "-q --turntable 2 --height " + (dir / "globe.tif").string() + " --exaggeration 40 --out ";
    ASSERT_EQ(render(turntable + (dir / "t{frame}.png").string() + " --aov " +
                     (dir / "t{frame}.exr").string())
                  .status,
              0);
    const test::RunResult path = render(turntable + (dir / "p{frame}.png").string() + " --aov " +
                                        (dir / "p{frame}.exr").string() + cache);
    ASSERT_EQ(path.status, 0) << path.err;
    EXPECT_EQ(readAov(dir / "p1.exr").pixels, readAov(dir / "t1.exr").pixels);

    // Rows of one camera file on both bases (a row's --base keeps its plane): each drawn
    // from the file built for its own base. Seen red: the renderer's "between the plane
    // and a curved base" when both rows shared the first's file.
    std::ofstream(dir / "cams.csv") << "eye_x,eye_y,eye_z,target_x,target_y,target_z,fovy,flags\n"
                                    << "0,2.2,0.0001,0,0,0,,\n"
                                    << "0,2.2,0.0001,0,0,0,,--base plane\n";
    const std::string rows = "-q --height " + (dir / "globe.tif").string() +
                             " --exaggeration 40 --cameras " + (dir / "cams.csv").string() +
                             " --out ";
    ASSERT_EQ(
        render(rows + (dir / "r{frame}.png").string() + " --aov " + (dir / "r{frame}.exr").string())
            .status,
        0);
    const test::RunResult both = render(rows + (dir / "c{frame}.png").string() + " --aov " +
                                        (dir / "c{frame}.exr").string() + cache);
    ASSERT_EQ(both.status, 0) << both.err;
    EXPECT_EQ(readAov(dir / "c0.exr").pixels, readAov(dir / "r0.exr").pixels);
    EXPECT_EQ(readAov(dir / "c1.exr").pixels, readAov(dir / "r1.exr").pixels);
    EXPECT_NE(readAov(dir / "c0.exr").pixels, readAov(dir / "c1.exr").pixels);

    // --compare-reference from a pyramid file traces the plane's reference: refused on the
    // ellipsoid the grid goes on, before anything is built (it compared the ellipsoid's
    // picture with the plane's reference: 97 % of the hits off).
    const test::RunResult compared =
        render(view + cache + " --compare-reference --out " + (dir / "x.png").string());
    EXPECT_EQ(compared.status, 2) << compared.out;
    EXPECT_NE(compared.err.find("not with --base ellipsoid"), std::string::npos) << compared.err;
}

TEST_F(DemRender, NodataSamplesLieAtTheLowestHeightAndFlagsAreChecked) {
    DemSpec spec;
    spec.width = spec.height = 32;
    spec.nodata = -9999.0;
    // A block of nodata in the middle of a 500 m plateau over a 200 m floor at the rim.
    spec.value = [](int i, int j) {
        if (i >= 12 && i < 20 && j >= 12 && j < 20) return -9999.0;
        return (i < 2 || j < 2 || i > 29 || j > 29) ? 200.0 : 500.0;
    };
    writeDem(dir / "holes.tif", spec, GDT_Int16);
    const test::RunResult r =
        render("--height " + (dir / "holes.tif").string() + " --out " + (dir / "h.png").string() +
               " --aov " + (dir / "h.exr").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("64 nodata samples filled with 200 m"), std::string::npos) << r.out;
    const Aov aov = readAov(dir / "h.exr");
    // The hole's middle (x, z within 2 samples of its centre) is at height 0, the plateau at
    // (500 - 200) / 960.
    int inHole = 0, onPlateau = 0;
    for (int y = 0; y < aov.height; ++y)
        for (int x = 0; x < aov.width; ++x) {
            const float* p = aov.at(x, y);
            if (p[3] == 0.0f) continue;
            const double i = (p[0] + 0.5) * 32.0, j = (p[2] + 0.5) * 32.0;
            if (std::abs(i - 16.0) < 2.0 && std::abs(j - 16.0) < 2.0) {
                ++inHole;
                EXPECT_NEAR(p[1], 0.0, 1e-6);
            } else if (i > 5 && i < 9 && j > 5 && j < 9) {
                ++onPlateau;
                EXPECT_NEAR(p[1], 300.0 / 960.0, 1e-5);
            }
        }
    EXPECT_GT(inHole, 20);
    EXPECT_GT(onPlateau, 20);

    const test::RunResult both =
        render("--height " + (dir / "holes.tif").string() +
               " --exaggeration 2 --height-scale 0.1 --out " + (dir / "x.png").string());
    test::expectOneLineFailure(both, "microrelief-render", 2, "give one");
    const test::RunResult zero = render("--height " + (dir / "holes.tif").string() +
                                        " --exaggeration 0 --out " + (dir / "x.png").string());
    test::expectOneLineFailure(zero, "microrelief-render", 2, "--exaggeration");
    // A height scale the fit makes unusable names the map and the exaggeration, not a flag
    // that was not given.
    const test::RunResult huge = render("--height " + (dir / "holes.tif").string() +
                                        " --exaggeration 1e300 --out " + (dir / "x.png").string());
    test::expectOneLineFailure(huge, "microrelief-render", 2,
                               "holes.tif: its true proportions at --exaggeration 1e+300");
    // --exaggeration over a plain image is said to do nothing.
    test::writeMap(dir / "plain.png", HeightMap(8, 8, 0.5f), PixelType::UInt8);
    const test::RunResult plain = render("--height " + (dir / "plain.png").string() +
                                         " --exaggeration 2 --out " + (dir / "x.png").string());
    EXPECT_EQ(plain.status, 0) << plain.err;
    EXPECT_NE(
        plain.err.find("--exaggeration: " + (dir / "plain.png").string() + " has no georeference"),
        std::string::npos)
        << plain.err;
}

// Once GDAL has read a DEM, a damaged TIFF read after it (an albedo, through OpenImageIO and
// the same libtiff) still fails in one line: GDAL's handler prints nothing.
TEST_F(DemRender, ADamagedTiffAfterADemFailsInOneLine) {
    DemSpec spec;
    writeDem(dir / "dem.tif", spec, GDT_Int16);
    test::writeMap(dir / "albedo.tif", HeightMap(8, 8, 0.5f), PixelType::UInt8);
    std::vector<std::uint8_t> bytes = test::readBytes(dir / "albedo.tif");
    ASSERT_GT(bytes.size(), 8u);
    for (int k = 4; k < 8; ++k) bytes[k] = 0xff;  // the first directory's offset, past the end
    test::writeBytes(dir / "albedo.tif", bytes);
    const test::RunResult r =
        render("--height " + (dir / "dem.tif").string() + " --albedo " +
               (dir / "albedo.tif").string() + " --out " + (dir / "x.png").string());
    test::expectOneLineFailure(r, "microrelief-render", 2, "albedo.tif");
}

#endif  // MICRORELIEF_WITH_GDAL

}  // namespace
