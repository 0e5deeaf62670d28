#include "SweepCases.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include "TestSupport.h"
#include "synth/SyntheticMaps.h"

namespace microrelief::test {

namespace {

std::shared_ptr<const HeightMap> share(HeightMap map) {
    return std::make_shared<const HeightMap>(std::move(map));
}

// Sparse one-texel spikes of full height on a zero floor.
HeightMap spikes(int n, std::uint32_t seed) {
    HeightMap map(n, n);
    const HeightMap dice = synth::whiteNoise(n, n, seed);
    for (std::size_t k = 0; k < map.samples.size(); ++k)
        map.samples[k] = dice.samples[k] > 0.985f ? 1.0f : 0.0f;
    return map;
}

// One-texel walls every `spacing` texels in both directions: a grid of thin fins.
HeightMap walls(int n, int spacing) {
    HeightMap map(n, n);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i)
            map.at(i, j) = (i % spacing == spacing / 2 || j % spacing == spacing / 2) ? 1.0f : 0.0f;
    }
    return map;
}

// Terraces: value noise quantised to 5 levels, so every contour is a cliff.
HeightMap cliffs(int n) {
    HeightMap map = synth::valueNoise(n, n, n / 4.0, 3, 17);
    for (float& h : map.samples) h = std::floor(h * 5.0f) / 5.0f;
    return map;
}

// A map that went through a file of the given type and back.
std::shared_ptr<const HeightMap> throughFile(const HeightMap& map, PixelType type,
                                             const std::string& name) {
    static ScratchDir scratch;
    const auto file = scratch / name;
    writeMap(file, map, type);
    return share(loadHeightMap(file));
}

}  // namespace

namespace {

// The list of maps, each made only when first needed: the GL sweep registers one test per
// entry (its count and names come from here), and building the 4096 map takes seconds.
struct SweepMapRecipe {
    const char* name;
    std::function<std::shared_ptr<const HeightMap>()> make;
    double heightScale;
};

const std::vector<SweepMapRecipe>& sweepMapRecipes() {
    static const std::vector<SweepMapRecipe> recipes = {
        {"noise", [] { return share(synth::whiteNoise(128, 128, 2)); }, 0.05},
        {"spikes", [] { return share(spikes(128, 4)); }, 0.1},
        {"walls", [] { return share(walls(128, 16)); }, 0.08},
        {"cliffs", [] { return share(cliffs(128)); }, 0.1},
        {"zero", [] { return share(synth::flat(16, 16, 0.0f)); }, 0.1},
        {"one", [] { return share(synth::flat(16, 16, 1.0f)); }, 0.1},
        {"oblong300x77", [] { return share(synth::valueNoise(300, 77, 10.0, 4, 8)); }, 0.1},
        {"single1x1", [] { return share(synth::flat(1, 1, 0.6f)); }, 0.1},
        {"tiny2x2", [] { return share(synth::whiteNoise(2, 2, 3)); }, 0.2},
        {"png16",
         [] {
             return throughFile(synth::cobbles(256, 256, 1), PixelType::UInt16, "cobbles16.png");
         },
         0.1},
        {"exrfloat",
         [] {
             HeightMap tall = synth::valueNoise(96, 96, 24.0, 4, 31);
             for (float& h : tall.samples) h *= 3.0f;  // float maps keep values above 1
             return throughFile(tall, PixelType::Float, "tall.exr");
         },
         0.03},
        {"huge4096", [] { return share(synth::valueNoise(4096, 4096, 256.0, 6, 5)); }, 0.1},
    };
    return recipes;
}

}  // namespace

std::size_t sweepMapCount() {
    return sweepMapRecipes().size();
}

std::string sweepMapName(std::size_t k) {
    return sweepMapRecipes().at(k).name;
}

const std::vector<SweepMap>& sweepMaps() {
    static const std::vector<SweepMap> maps = [] {
        std::vector<SweepMap> built;
        for (const SweepMapRecipe& r : sweepMapRecipes())
            built.push_back({r.name, r.make(), r.heightScale});
        return built;
    }();
    return maps;
}

std::vector<SweepView> sweepViews(const SweepMap& m) {
    std::vector<SweepView> views;
    const HeightMap& map = *m.map;
    const double top = m.heightScale * map.maxValue();
    const glm::dvec3 centre(0.0, 0.5 * top, 0.0);
    // The 4096 map is the costly one: a few views suffice to show size does not matter.
    const bool few = map.width * map.height > 1024 * 1024;
    const std::vector<double> elevations =
        few ? std::vector<double>{90, 30, 3} : std::vector<double>{90, 60, 30, 10, 3, 1};
    const std::vector<double> azimuths =
        few ? std::vector<double>{37} : std::vector<double>{0, 37, 135, 250};
    for (double e : elevations) {
        for (double a : azimuths) {
            if (e == 90 && a != azimuths.front()) continue;  // one top view is enough
            views.push_back({"e" + std::to_string(static_cast<int>(e)) + "a" +
                                 std::to_string(static_cast<int>(a)),
                             orbitCamera(e, a, 1.6, centre, 45.0)});
        }
    }
    // Inside the box, above the surface: over the lowest sample, halfway up to the top.
    const auto lowest =
        std::min_element(map.samples.begin(), map.samples.end()) - map.samples.begin();
    const int i = static_cast<int>(lowest % map.width), j = static_cast<int>(lowest / map.width);
    const double longer = std::max(map.width, map.height);
    const glm::dvec3 ground((i + 0.5 - 0.5 * map.width) / longer, m.heightScale * map.at(i, j),
                            (j + 0.5 - 0.5 * map.height) / longer);
    if (top > ground.y) {
        Camera inside;
        inside.eye = ground + glm::dvec3(0.0, 0.5 * (top - ground.y), 0.0);
        inside.target = glm::dvec3(-0.5 * inside.eye.x + 0.1, ground.y, -0.5 * inside.eye.z + 0.07);
        inside.fovyDegrees = 80.0;
        views.push_back({"inside", inside});
    }
    Camera below;
    below.eye = {0.35, -0.7, 0.25};
    views.push_back({"below", below});
    views.push_back({"far", orbitCamera(35.0, 60.0, 40.0, centre, 20.0)});
    Camera close;
    close.eye = glm::dvec3(0.05, top + 0.04, 0.03);
    close.target = glm::dvec3(0.0, 0.5 * top, 0.0);
    close.fovyDegrees = 60.0;
    views.push_back({"close", close});
    return views;
}

PixelHit twinPixel(const MultilevelTracer& twin, const Ray& ray) {
    TraversalStats stats;
    const auto hit = twin.intersect(ray, &stats);
    return PixelHit{hit.has_value(), hit ? hit->position : glm::dvec3(0.0), stats.exhausted};
}

std::vector<SweepCase> sweepCases() {
    std::vector<SweepCase> cases;
    for (const SweepMap& map : sweepMaps()) {
        for (SweepView& view : sweepViews(map)) cases.push_back({&map, std::move(view)});
    }
    return cases;
}

}  // namespace microrelief::test
