#include "microrelief/core/synth/SyntheticMaps.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "microrelief/core/Error.h"

namespace microrelief::synth {

namespace {

// A small integer hash (lowbias32): deterministic across platforms, unlike <random>'s
// distributions.
std::uint32_t hash(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

double unitHash(std::int64_t i, std::int64_t j, std::uint32_t seed) {
    const std::uint32_t h = hash(static_cast<std::uint32_t>(i) * 0x9e3779b9U ^
                                 hash(static_cast<std::uint32_t>(j) + seed));
    return (h >> 8) * (1.0 / 16777216.0);
}

// Value noise on a lattice of period 1 at (x, y), smoothstep-interpolated, in [0, 1].
double latticeNoise(double x, double y, std::uint32_t seed) {
    const double fx = std::floor(x), fy = std::floor(y);
    const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
    auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
    const double sx = smooth(x - fx), sy = smooth(y - fy);
    const double a = unitHash(i, j, seed), b = unitHash(i + 1, j, seed);
    const double c = unitHash(i, j + 1, seed), d = unitHash(i + 1, j + 1, seed);
    return (a + (b - a) * sx) * (1 - sy) + (c + (d - c) * sx) * sy;
}

// Value noise on the unit lattice in space, smoothstep-interpolated, in [0, 1].
double latticeNoise3(const double p[3], std::uint32_t seed) {
    double f[3], s[3];
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a) {
        const double floor = std::floor(p[a]);
        c[a] = static_cast<std::int64_t>(floor);
        f[a] = p[a] - floor;
        s[a] = f[a] * f[a] * (3.0 - 2.0 * f[a]);
    }
    double sum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        const int dx = corner & 1, dy = (corner >> 1) & 1, dz = corner >> 2;
        const double w = (dx ? s[0] : 1 - s[0]) * (dy ? s[1] : 1 - s[1]) * (dz ? s[2] : 1 - s[2]);
        sum += w *
               unitHash(c[0] + dx, c[1] + dy, seed + 7919U * static_cast<std::uint32_t>(c[2] + dz));
    }
    return sum;
}

double fractalNoise(double x, double y, int octaves, std::uint32_t seed) {
    double sum = 0.0, amplitude = 1.0, total = 0.0;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * latticeNoise(x, y, seed + 1013U * o);
        total += amplitude;
        x *= 2.0;
        y *= 2.0;
        amplitude *= 0.5;
    }
    return sum / total;
}

}  // namespace

HeightMap flat(int width, int height, float value) {
    return HeightMap(width, height, value);
}

HeightMap spike(int width, int height, int i, int j) {
    HeightMap map(width, height);
    map.at(i, j) = 1.0f;
    return map;
}

HeightMap wallColumn(int width, int height, int i) {
    HeightMap map(width, height);
    for (int j = 0; j < height; ++j) map.at(i, j) = 1.0f;
    return map;
}

HeightMap step(int width, int height, int i0) {
    HeightMap map(width, height);
    for (int j = 0; j < height; ++j) {
        for (int i = i0; i < width; ++i) map.at(i, j) = 1.0f;
    }
    return map;
}

HeightMap valueNoise(int width, int height, double period, int octaves, std::uint32_t seed) {
    HeightMap map(width, height);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            map.at(i, j) = static_cast<float>(
                fractalNoise((i + 0.5) / period, (j + 0.5) / period, octaves, seed));
        }
    }
    return map;
}

HeightMap whiteNoise(int width, int height, std::uint32_t seed) {
    HeightMap map(width, height);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) map.at(i, j) = static_cast<float>(unitHash(i, j, seed));
    }
    return map;
}

namespace {

// The cobble pattern at point (x, y) of its grid (6 cells per map side): the stone's hash,
// how far inside its cell the point lies (0 at the border, 1 well inside), and the grain.
struct Cobble {
    double stone = 0.0, edge = 0.0, grain = 0.0;
    std::int64_t cellI = 0, cellJ = 0;
};

Cobble cobbleAt(double x, double y, std::uint32_t seed) {
    // Stones are Voronoi cells of jittered points; a stone's height rises with the
    // distance to its cell border (F2 - F1).
    const auto ci = static_cast<std::int64_t>(std::floor(x)),
               cj = static_cast<std::int64_t>(std::floor(y));
    double f1 = 1e9, f2 = 1e9;
    Cobble c;
    for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
            const std::int64_t gi = ci + di, gj = cj + dj;
            const double px = gi + 0.15 + 0.7 * unitHash(gi, gj, seed);
            const double py = gj + 0.15 + 0.7 * unitHash(gi, gj, seed + 7U);
            const double d = std::hypot(x - px, y - py);
            if (d < f1) {
                f2 = f1;
                f1 = d;
                c.stone = unitHash(gi, gj, seed + 13U);
                c.cellI = gi;
                c.cellJ = gj;
            } else if (d < f2) {
                f2 = d;
            }
        }
    }
    c.edge = std::clamp((f2 - f1) / 0.35, 0.0, 1.0);
    c.grain = fractalNoise(x * 5.0, y * 5.0, 3, seed + 99U);
    return c;
}

constexpr double kCobbleCells = 6.0;

}  // namespace

HeightMap cobbles(int width, int height, std::uint32_t seed) {
    HeightMap map(width, height);
    cobblesRows(width, height, seed, 0, height, map.samples.data());
    return map;
}

void cobblesRows(int width, int height, std::uint32_t seed, int y0, int y1, float* out) {
    const double longer = std::max(width, height);
    for (int j = y0; j < y1; ++j) {
        for (int i = 0; i < width; ++i) {
            const double x = (i + 0.5) / longer * kCobbleCells,
                         y = (j + 0.5) / longer * kCobbleCells;
            const Cobble c = cobbleAt(x, y, seed);
            const double dome =
                std::sqrt(1.0 - (1.0 - c.edge) * (1.0 - c.edge));  // rounded shoulders
            const double h = dome * (0.72 + 0.2 * c.stone) + 0.08 * c.grain * dome + 0.03 * c.grain;
            out[static_cast<std::size_t>(j - y0) * width + i] =
                static_cast<float>(std::clamp(h, 0.0, 1.0));
        }
    }
}

namespace {

// The planet at (u, v): noise of the point on the unit sphere, so the map is seamless in u
// and smooth at the poles: fBm continents (`coast`: 0 sea, 1 inland) with ridged
// mountains.
struct PlanetPoint {
    double coast = 0.0, ridges = 0.0, latitude = 0.0;  // latitude: -1 south pole, 1 north
};

PlanetPoint planetAt(double u, double v, std::uint32_t seed) {
    constexpr double pi = 3.14159265358979323846;
    const double theta = pi * v, phi = 2.0 * pi * (u - 0.5);
    const double w[3] = {std::sin(theta) * std::sin(phi), std::cos(theta),
                         std::sin(theta) * std::cos(phi)};
    double land = 0.0, ridges = 0.0, amplitude = 1.0, total = 0.0;
    for (int octave = 0; octave < 7; ++octave) {
        const double scale = 1.6 * std::ldexp(1.0, octave);
        const double p[3] = {w[0] * scale, w[1] * scale, w[2] * scale};
        const double n = latticeNoise3(p, seed + 101U * octave);
        land += amplitude * n;
        ridges += amplitude * (1.0 - std::abs(2.0 * n - 1.0));
        total += amplitude;
        amplitude *= 0.5;
    }
    land /= total;
    ridges /= total;
    return {std::clamp((land - 0.47) * 5.0, 0.0, 1.0), ridges, w[1]};
}

double planetHeight(const PlanetPoint& p) {
    return p.coast * (0.15 + 0.85 * p.ridges * p.ridges);
}

}  // namespace

HeightMap planet(int width, int height, std::uint32_t seed) {
    HeightMap map(width, height);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            const PlanetPoint p = planetAt((i + 0.5) / width, (j + 0.5) / height, seed);
            map.at(i, j) = static_cast<float>(planetHeight(p));
        }
    }
    return map;
}

namespace {

using Rgb = std::array<double, 3>;

Rgb mix(const Rgb& a, const Rgb& b, double t) {
    return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

// Stones from a small palette of building stones (linear RGB), each a little lighter or
// darker, with a fine grain; the joints between them sandy and darker where they meet
// the stones.
Rgb cobbleColour(double x, double y, std::uint32_t seed) {
    static const Rgb palette[] = {{0.16, 0.16, 0.17}, {0.35, 0.22, 0.11}, {0.20, 0.12, 0.07},
                                  {0.32, 0.11, 0.07}, {0.09, 0.11, 0.15}, {0.28, 0.27, 0.24}};
    const Cobble c = cobbleAt(x, y, seed);
    const int pick = static_cast<int>(c.stone * 6.0) % 6;
    const double shade = 0.8 + 0.4 * unitHash(c.cellI, c.cellJ, seed + 31U);
    const double fine = fractalNoise(x * 40.0, y * 40.0, 3, seed + 57U);
    Rgb stone = palette[pick];
    for (double& channel : stone) channel *= shade * (0.85 + 0.3 * fine);
    const Rgb joint = mix({0.05, 0.045, 0.04}, {0.14, 0.12, 0.09}, fine);
    return mix(joint, stone, std::clamp((c.edge - 0.08) / 0.12, 0.0, 1.0));
}

// Deep and shallow sea, lowland green, dry upland, rock and snow by height, ice caps by
// latitude.
Rgb planetColour(double u, double v, std::uint32_t seed) {
    const PlanetPoint p = planetAt(u, v, seed);
    const double h = planetHeight(p);
    Rgb colour = mix({0.01, 0.03, 0.12}, {0.03, 0.12, 0.25}, p.coast > 0.0 ? 1.0 : 0.6);
    if (p.coast > 0.0) {
        colour =
            mix({0.08, 0.20, 0.05}, {0.30, 0.24, 0.13}, std::clamp((h - 0.15) / 0.3, 0.0, 1.0));
        colour = mix(colour, {0.35, 0.34, 0.33}, std::clamp((h - 0.45) / 0.25, 0.0, 1.0));
        colour = mix(colour, {0.85, 0.86, 0.88}, std::clamp((h - 0.75) / 0.15, 0.0, 1.0));
    }
    return mix(colour, {0.80, 0.83, 0.88},
               std::clamp((std::abs(p.latitude) - 0.95) / 0.02, 0.0, 1.0));
}

}  // namespace

AlbedoImage albedo(const std::string& name, int width, int height, int mapWidth, int mapHeight,
                   std::uint32_t seed) {
    if (width <= 0 || height <= 0) throwBadInput("the albedo size must be positive");
    if (name != "cobbles" && name != "planet")
        throwBadInput("no albedo for the map '" + name + "' (cobbles and planet have one)");
    AlbedoImage image;
    image.width = width;
    image.height = height;
    image.linear.resize(static_cast<std::size_t>(width) * height * 4);
    const double longer = std::max(mapWidth, mapHeight);
    for (int j = 0; j < height; ++j) {
        for (int i = 0; i < width; ++i) {
            // The same (u, v) as the height map's: its grid spans the map's longer side.
            const double u = (i + 0.5) / width, v = (j + 0.5) / height;
            const Rgb rgb = name == "cobbles"
                                ? cobbleColour(u * mapWidth / longer * kCobbleCells,
                                               v * mapHeight / longer * kCobbleCells, seed)
                                : planetColour(u, v, seed);
            float* out = &image.linear[(static_cast<std::size_t>(j) * width + i) * 4];
            for (int c = 0; c < 3; ++c)
                out[c] = static_cast<float>(rgb[static_cast<std::size_t>(c)]);
            out[3] = 1.0f;
        }
    }
    return image;
}

std::vector<std::string> names() {
    return {"cobbles", "noise", "white", "spike", "wall", "step", "flat", "planet"};
}

HeightMap byName(const std::string& name, int width, int height, std::uint32_t seed) {
    if (width <= 0 || height <= 0) throwBadInput("the map size must be positive");
    if (name == "cobbles") return cobbles(width, height, seed);
    if (name == "noise") return valueNoise(width, height, std::max(width, height) / 8.0, 5, seed);
    if (name == "white") return whiteNoise(width, height, seed);
    if (name == "spike") return spike(width, height, width / 2, height / 2);
    if (name == "wall") return wallColumn(width, height, width / 2);
    if (name == "step") return step(width, height, width / 2);
    if (name == "flat") return flat(width, height, 0.5f);
    if (name == "planet") return planet(width, height, seed);
    std::string known;
    for (const std::string& n : names()) known += (known.empty() ? "" : ", ") + n;
    throwBadInput("unknown map '" + name + "' (known: " + known + ")");
}

}  // namespace microrelief::synth
