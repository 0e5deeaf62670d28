// Builds a max pyramid from an engine's own 16-bit samples (a pointer, a size and a row
// stride) and traces a ray straight down with the CPU twin of the shader; prints the
// pyramid's shape and the hit.
#include <cstdint>
#include <cstdio>
#include <vector>

#include "microrelief/Version.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/trace/MultilevelTracer.h"

int main() {
    // A 5 x 3 map in rows of 8 samples (a padded image): a ramp, 65535 at its highest.
    const int width = 5, height = 3, stride = 8;
    std::vector<std::uint16_t> image(stride * height, 0);
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i)
            image[j * stride + i] = static_cast<std::uint16_t>(i * 16383);
    const microrelief::HeightMap map = microrelief::heightMapFromSamples(
        image.data(), width, height, stride * sizeof(std::uint16_t));
    const microrelief::MaxPyramid pyramid(map);
    std::printf("microrelief %s: %d levels, finest %dx%d, top %.4f\n",
                microrelief::libraryVersion(), pyramid.windowLevelCount(),
                pyramid.windowLevelWidth(0), pyramid.windowLevelHeight(0), pyramid.maxHeight());
    // Down onto the middle of the map: the ramp's height there is 0.5, times the scale 0.1.
    const microrelief::MultilevelTracer twin(map, 0.1);
    const auto hit = twin.intersect({{0.0, 1.0, 0.0}, {0.0, -1.0, 0.0}});
    if (!hit) return 1;
    std::printf("hit at y = %.6f\n", hit->position.y);
    return 0;
}
