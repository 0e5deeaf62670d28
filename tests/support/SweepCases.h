// The accuracy sweep of issue 3: maps that defeat step-based methods (noise, one-texel
// spikes and walls, cliffs), degenerate and odd maps, maps read from 16-bit and float
// files, a 4096 x 4096 map; each seen from 90 degrees down to 1 degree above the
// surface at several azimuths, and from the awkward places (inside the box, below the
// base plane, far away, very close).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "heightmap/HeightMap.h"
#include "render/Camera.h"

namespace microrelief::test {

struct SweepMap {
    std::string name;
    std::shared_ptr<const HeightMap> map;
    double heightScale;
};

struct SweepView {
    std::string name;
    Camera camera;
};

struct SweepCase {
    const SweepMap* map;
    SweepView view;
    std::string name() const { return map->name + "_" + view.name; }
};

// Built once per process (the 4096 map takes a moment); `scratch` holds the files the
// 16-bit and float maps are written to and read back from.
const std::vector<SweepMap>& sweepMaps();
std::vector<SweepView> sweepViews(const SweepMap& map);
std::vector<SweepCase> sweepCases();

// Picture size for a case: small, since every pixel is also traced on the CPU.
constexpr int kSweepSize = 64;

}  // namespace microrelief::test
