// Procedural height maps: the bundled default map, the features the tests and the
// accuracy sweep need (one-texel spikes and walls, steps, noise), at any size. All are
// deterministic for a given seed, so a map of any size can be remade exactly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/image/Albedo.h"

namespace microrelief::synth {

HeightMap flat(int width, int height, float value);
// Value 1 at sample (i, j), 0 elsewhere.
HeightMap spike(int width, int height, int i, int j);
// Value 1 on column i (a wall one texel thick across the map), 0 elsewhere.
HeightMap wallColumn(int width, int height, int i);
// 0 for columns < i, 1 from column i on.
HeightMap step(int width, int height, int i);
// Smooth value noise with `octaves` octaves in [0, 1], cell size `period` texels.
HeightMap valueNoise(int width, int height, double period, int octaves, std::uint32_t seed);
// Independent uniform [0, 1) per sample: the roughest relief.
HeightMap whiteNoise(int width, int height, std::uint32_t seed);
// Rounded cobblestones with mortar joints and fine grain: the bundled default map.
// Sizes are relative, so the same relief comes out at any resolution.
HeightMap cobbles(int width, int height, std::uint32_t seed);
// Rows y0 .. y1 - 1 of cobbles(width, height, seed) into `out` (width a row), the same
// samples: a map of any size made a band at a time (microrelief-bench --terrain).
void cobblesRows(int width, int height, std::uint32_t seed, int y0, int y1, float* out);

// Continents and ridged mountains over a flat sea, an equirectangular map for a globe
// (--base sphere): seamless in u, smooth at the poles.
HeightMap planet(int width, int height, std::uint32_t seed);

// Names accepted by byName(): cobbles, noise, white, spike, wall, step, flat, planet.
std::vector<std::string> names();

// A matching colour texture for the map `name` of mapWidth x mapHeight (the same seed):
// coloured stones and their joints for "cobbles", seas, land, rock, snow and ice for
// "planet"; width x height pixels, linear RGB. Throws Error(BadInput) for other maps.
AlbedoImage albedo(const std::string& name, int width, int height, int mapWidth, int mapHeight,
                   std::uint32_t seed);
// Throws Error(BadInput) for an unknown name.
HeightMap byName(const std::string& name, int width, int height, std::uint32_t seed);

}  // namespace microrelief::synth
