// The cone maps' test cases (peers/ConeMap.h), shared by the CPU build's tests
// (tests/cpu/ConeMapTest.cpp) and the GPU build's (tests/gl/ConePeerTest.cpp): random and
// adversarial small maps: spikes, one-texel walls, steps, ramps, periodic relief, white
// noise (the roughest), a pit in a plateau, scales from 1e-3 to 1e3 (ratios near the half
// floats' ends), heights down to 1e-22, and relief 3 high on a base 3000 high. And the
// GPU build's check against the CPU build (tests/gl/ConePeerTest.cpp, the programs' GL;
// tests/web/WebPageTest.cpp, the page's WebGL).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/peers/ConeMap.h"

namespace microrelief::test {

struct ConeCase {
    std::string name;
    HeightMap map;
};

std::vector<ConeCase> coneCases();

// A conservative cone map drawn on a GPU (shaders/pyramid/cone_map.frag) against the CPU
// build of the same map (buildConservativeConeMap): what the GPU build promises is every
// apex the CPU's bit for bit and no ratio above the CPU's (so every GPU cone inside a CPU
// cone, which tests/cpu/ConeMapTest.cpp holds free of the surface); most ratios the same.
struct GpuConeMapCheck {
    std::size_t texels = 0, same = 0;     // ratios in all, and the CPU's
    std::size_t wrong = 0;                // texels that break the promise
    int mostHalvesBelow = 0;              // the farthest ratio below the CPU's, in halves
    std::vector<std::string> firstWrong;  // the first three, named

    // Adds `gpu` against `cpu`, the map `name` `width` texels wide.
    void add(const std::string& name, int width, const ConeMap& gpu, const ConeMap& cpu);
    // "N of M ratios the CPU's, K wider or off in the apex, at most H halves narrower".
    std::string summary() const;
};

// gtest prints a failing case's parameter: its name, not its bytes.
inline void PrintTo(const ConeCase& c, std::ostream* out) {
    *out << c.name;
}

}  // namespace microrelief::test
