// What a georeferenced elevation model (a GeoTIFF DEM and its kind, read by the io
// component: io/HeightMapFile.h) says about its samples, and the relief that draws it with
// its true proportions (docs/terrain.md). The io component reads the samples as metres,
// fills the nodata samples with the lowest valid height and maps [lowest, highest] to
// [0, 1]; fitToGeoreference then gives the relief the height scale (and, on the plane, the
// horizontal stretch) that puts those heights back at their size against the ground.
#pragma once

#include <cstddef>
#include <string>

#include "microrelief/core/scene/Scene.h"

namespace microrelief {

struct Georeference {
    // The ground size of one sample, metres: across the map (u, east in a north-up grid)
    // and down it (v). A latitude/longitude grid's at its centre latitude.
    double sampleWidthMetres = 1.0, sampleHeightMetres = 1.0;
    // The valid samples' range, metres: map value 0 and map value 1.
    double lowestMetres = 0.0, highestMetres = 0.0;
    // A latitude/longitude grid, and one that covers the whole globe (360 degrees of
    // longitude, 180 of latitude, to half a sample).
    bool geographic = false, global = false;
    // A latitude/longitude grid's ellipsoid, metres (0 for a projected grid).
    double semiMajorMetres = 0.0, semiMinorMetres = 0.0;
    // Samples the file marks as having no data, filled with the lowest valid height.
    std::size_t nodataSamples = 0;
    // The coordinate system's name ("WGS 84 / UTM zone 33N"); empty where the file gives a
    // grid but no system, whose units are then taken as metres.
    std::string crs;

    bool operator==(const Georeference&) const = default;
};

// Whether a sample is square on the ground (its sides equal to a part in 1e9): then the
// plane needs no stretch for it.
bool squareSamples(const Georeference& geo);

// The ground length of one degree along a parallel (east) and along a meridian (north), in
// metres, at geodetic latitude `latitudeDegrees` on the ellipsoid of semi-axes a >= b:
// N cos(phi) pi / 180 and M pi / 180, N and M the radii of curvature in the prime vertical
// and the meridian.
double metresPerDegreeEast(double a, double b, double latitudeDegrees);
double metresPerDegreeNorth(double a, double b, double latitudeDegrees);

// Which of the relief's values the georeference may set: those a user gave are kept.
struct GeoreferenceFit {
    double exaggeration = 1.0;  // the vertical exaggeration: heights times this
    bool keepHeightScale = false, keepModel = false, keepBase = false;
};

// Sets the relief of a W x H georeferenced map to its true proportions, where `fit` lets
// (W and H: the map's own; the relief's tiles repeat it, and the ground with it):
// - a global latitude/longitude grid goes on the ellipsoid of the grid's own axes, scaled
//   to a semi-major radius of 0.5 (radii 0.5, 0.5 b / a, 0.5);
// - the height scale makes the map's range (highest - lowest metres) stand at its size
//   against the ground, times the exaggeration: on the plane, whose longer ground side spans
//   one world unit, s = range / max(W dx, H dy); on a curved base, whose canonical radius is
//   the ground's, s = range / radius, the radius being the ellipsoid's semi-major axis for a
//   global grid and W dx / (2 pi) (the map's width round the base) otherwise. A map with
//   no range keeps its height scale;
// - on the plane, samples that are not square on the ground (dx != dy) stretch the model
//   along x and z so that the map's sides stand in their ground ratio (the plane itself
//   gives them the ratio of W to H).
// The base fitToGeoreference gives a relief on `base` over a map with `geo`: the ellipsoid
// for a global latitude/longitude grid where `fit` lets, else `base`. Reads only the grid's
// fields (geographic, global, the axes), which a header holds (io: readMapGrid).
BaseShape fittedBase(const BaseShape& base, const Georeference& geo, const GeoreferenceFit& fit);
void fitToGeoreference(ReliefDesc& relief, int width, int height, const Georeference& geo,
                       const GeoreferenceFit& fit);

}  // namespace microrelief
