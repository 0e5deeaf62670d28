// The cone maps' test cases (peers/ConeMap.h), shared by the CPU build's tests
// (tests/cpu/ConeMapTest.cpp) and the GPU build's (tests/gl/ConePeerTest.cpp): random and
// adversarial small maps: spikes, one-texel walls, steps, ramps, periodic relief, white
// noise (the roughest), a pit in a plateau, scales from 1e-3 to 1e3 (ratios near the half
// floats' ends), heights down to 1e-22, and relief 3 high on a base 3000 high.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "microrelief/core/heightmap/HeightMap.h"

namespace microrelief::test {

struct ConeCase {
    std::string name;
    HeightMap map;
};

std::vector<ConeCase> coneCases();

// gtest prints a failing case's parameter: its name, not its bytes.
inline void PrintTo(const ConeCase& c, std::ostream* out) {
    *out << c.name;
}

}  // namespace microrelief::test
