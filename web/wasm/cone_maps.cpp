// cone_maps.cpp: the relaxed cone maps of the peer rcsm (microrelief::peers, ConeMap.h,
// unchanged) behind a C interface for the web page, compiled to WebAssembly by the build
// (web/CMakeLists.txt) into web/generated/cone_maps_wasm.js. The page builds them from
// the samples it uploads, as ReliefTextures::addConeMap builds them on the CPU from the
// samples the GPU holds: the same functions on the same floats, so the same RG16F texels to
// the bit (tests/web: ThePageConeMapsAreTheCppOnes). Cone's conservative map is drawn on the
// GPU in the page as in the programs (shaders/pyramid/cone_map.frag).
#include <emscripten.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "microrelief/peers/ConeMap.h"

using namespace microrelief;

namespace {
std::string lastError;
}  // namespace

// The worker's message {id, progress} to the page: `done`, the fraction of the rows built.
EM_JS(void, mr_post_progress, (int job, double done),
      { postMessage({id : job, progress : done}); });

extern "C" {

// rcsm's relaxed cone map of `samples` (width x height floats, row 0 first) into `texels`
// (2 width x height halves: apex, ratio per texel, row 0 first), with 128 search steps, as
// published and as ReliefTextures builds it. As it goes, the worker posts {id: job, progress} with
// the fraction of the rows done, at most once a whole percent. 1 when done, 0 with mr_last_error()
// saying why.
int mr_build_relaxed_cone_map(const float* samples, int width, int height, std::uint16_t* texels,
                              int job) {
    try {
        HeightMap map(width, height);
        std::memcpy(map.samples.data(), samples, map.samples.size() * sizeof(float));
        int percent = 0;
        const ConeMapProgress progress = [&](double done) {
            if (std::floor(done * 100.0) <= percent) return;
            percent = static_cast<int>(std::floor(done * 100.0));
            mr_post_progress(job, done);
        };
        const ConeMap cones = buildRelaxedConeMap(map, 128, nullptr, progress);
        const std::vector<std::uint16_t> halves = coneMapHalfTexels(cones);
        std::memcpy(texels, halves.data(), halves.size() * sizeof(std::uint16_t));
        return 1;
    } catch (const std::exception& e) {
        lastError = e.what();
        return 0;
    }
}

const char* mr_last_error() {
    return lastError.c_str();
}
}
