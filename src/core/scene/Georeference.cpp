#include "microrelief/core/scene/Georeference.h"

#include <algorithm>
#include <cmath>

namespace microrelief {

namespace {

constexpr double kPi = 3.14159265358979323846;

// e^2 = 1 - b^2 / a^2 and 1 - e^2 sin^2(phi), for the radii of curvature.
double eccentricitySquared(double a, double b) {
    return 1.0 - (b * b) / (a * a);
}
double curvatureDenominator(double a, double b, double latitudeDegrees) {
    const double s = std::sin(latitudeDegrees * kPi / 180.0);
    return 1.0 - eccentricitySquared(a, b) * s * s;
}

}  // namespace

bool squareSamples(const Georeference& geo) {
    const double dx = geo.sampleWidthMetres, dy = geo.sampleHeightMetres;
    return std::abs(dx - dy) <= 1e-9 * std::max(dx, dy);
}

double metresPerDegreeEast(double a, double b, double latitudeDegrees) {
    const double n = a / std::sqrt(curvatureDenominator(a, b, latitudeDegrees));
    return n * std::cos(latitudeDegrees * kPi / 180.0) * kPi / 180.0;
}

double metresPerDegreeNorth(double a, double b, double latitudeDegrees) {
    const double m = a * (1.0 - eccentricitySquared(a, b)) /
                     std::pow(curvatureDenominator(a, b, latitudeDegrees), 1.5);
    return m * kPi / 180.0;
}

BaseShape fittedBase(const BaseShape& base, const Georeference& geo, const GeoreferenceFit& fit) {
    if (!fit.keepBase && geo.geographic && geo.global)
        return BaseShape::ellipsoid(
            glm::dvec3(0.5, 0.5 * geo.semiMinorMetres / geo.semiMajorMetres, 0.5));
    return base;
}

void fitToGeoreference(ReliefDesc& relief, int width, int height, const Georeference& geo,
                       const GeoreferenceFit& fit) {
    relief.base = fittedBase(relief.base, geo, fit);

    // The whole the base carries: the map repeated tiles.x x tiles.y times (--tile).
    width *= relief.tiles.x;
    height *= relief.tiles.y;
    const double groundWidth = width * geo.sampleWidthMetres;
    const double groundHeight = height * geo.sampleHeightMetres;
    const double range = geo.highestMetres - geo.lowestMetres;
    if (!fit.keepHeightScale && range > 0.0) {
        double metresPerUnit = std::max(groundWidth, groundHeight);  // the plane's longer side
        if (relief.base.curved())
            metresPerUnit =
                geo.geographic && geo.global ? geo.semiMajorMetres : groundWidth / (2.0 * kPi);
        relief.heightScale = static_cast<float>(range / metresPerUnit * fit.exaggeration);
    }

    // The plane puts the map's sides in the ratio W : H (a = W / max(W, H)); the ground's is
    // W dx : H dy. Square samples need no stretch.
    if (!fit.keepModel && !relief.base.curved() && !squareSamples(geo)) {
        const double longest = std::max(groundWidth, groundHeight);
        const double side = std::max(width, height);
        glm::dmat4 stretch(1.0);
        stretch[0][0] = (groundWidth / longest) / (width / side);
        stretch[2][2] = (groundHeight / longest) / (height / side);
        relief.model = ModelTransform(stretch);
    }
}

}  // namespace microrelief
