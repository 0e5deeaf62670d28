#include "SweepCases.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>

#include "TestSupport.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/core/synth/SyntheticMaps.h"

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

// Noise whose first and last columns differ sharply: the seam of a curved base, where
// the surface climbs from 0 (columns 0, 1) to 1 (columns W - 2, W - 1) across u = 0.
HeightMap seamMap(int w, int h) {
    HeightMap map = synth::valueNoise(w, h, 8.0, 3, 23);
    for (int j = 0; j < h; ++j) {
        map.at(0, j) = map.at(1, j) = 0.0f;
        map.at(w - 2, j) = map.at(w - 1, j) = 1.0f;
    }
    return map;
}

// The list of maps, each made only when first needed: the GL sweep registers one test per
// entry (its count and names come from here), and building the 4096 map takes seconds.
using MakeMap = std::function<std::shared_ptr<const HeightMap>()>;

struct SweepMapRecipe {
    std::string name;
    MakeMap make;
    double heightScale;
    BaseShape base = {};
    Interpolation interpolation = Interpolation::Bilinear;
};

// `make` run once, its map shared by every recipe that holds the result.
MakeMap once(MakeMap make) {
    auto made = std::make_shared<std::shared_ptr<const HeightMap>>();
    return [made, make = std::move(make)] {
        if (!*made) *made = make();
        return *made;
    };
}

// The curved bases' maps: the seam, real-looking and rough relief, spikes, odd and
// non-square sizes (wider and narrower than tall), 1 x 1, a 16-bit PNG and a float EXR; each on a
// cylinder and on an ellipsoid (a sphere for some).
void addCurvedRecipes(std::vector<SweepMapRecipe>& recipes) {
    const std::vector<std::pair<std::string, std::pair<MakeMap, double>>> relief = {
        {"seam", {[] { return share(seamMap(96, 48)); }, 0.15}},
        {"cobbles", {[] { return share(synth::cobbles(128, 128, 5)); }, 0.12}},
        {"white", {[] { return share(synth::whiteNoise(64, 32, 9)); }, 0.1}},
        {"spikes", {[] { return share(spikes(96, 6)); }, 0.2}},
        {"oblong75x33", {[] { return share(synth::valueNoise(75, 33, 6.0, 3, 12)); }, 0.15}},
        {"single1x1", {[] { return share(synth::flat(1, 1, 0.6f)); }, 0.1}},
        {"png16",
         {[] { return throughFile(synth::cobbles(128, 64, 3), PixelType::UInt16, "globe16.png"); },
          0.1}},
        {"exrfloat",
         {[] {
              HeightMap tall = synth::valueNoise(60, 30, 10.0, 3, 41);
              for (float& h : tall.samples) h *= 2.0f;  // float maps keep values above 1
              return throughFile(tall, PixelType::Float, "tall-curved.exr");
          },
          0.06}},
        // Narrower than tall: levels with one column of pyramid nodes round the axis.
        {"tall33x75", {[] { return share(synth::valueNoise(33, 75, 6.0, 3, 13)); }, 0.15}},
        // Two samples round: the seam cell's far edge is half a turn from its near one
        // (relief_patch.glsl: mr_patchLocal took it for the other corner).
        {"two2x24", {[] { return share(synth::whiteNoise(2, 24, 5)); }, 0.3}},
    };
    for (std::size_t k = 0; k < relief.size(); ++k) {
        const auto& [name, data] = relief[k];
        const MakeMap make = once(data.first);
        recipes.push_back({"cylinder_" + name, make, data.second, BaseShape::cylinder(0.3, 0.8)});
        // Alternately a sphere and an ellipsoid of unequal radii.
        recipes.push_back(
            {(k % 2 ? "ellipsoid_" : "sphere_") + name, make, data.second,
             k % 2 ? BaseShape::ellipsoid({0.45, 0.35, 0.3}) : BaseShape::sphere(0.4)});
    }
}

const std::vector<SweepMapRecipe>& sweepMapRecipes() {
    static const std::vector<SweepMapRecipe> recipes = [] {
        std::vector<SweepMapRecipe> all = {
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
                 return throughFile(synth::cobbles(256, 256, 1), PixelType::UInt16,
                                    "cobbles16.png");
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
        for (SweepMapRecipe& r : all) r.make = once(std::move(r.make));
        addCurvedRecipes(all);
        // The biquadratic surface on the maps that stress it most: the one-texel features
        // (its patches overshoot nothing but spread each spike over 3 x 3 squares), the
        // cliffs, odd and tiny sizes, floats above 1, the 4096 map, the seam (whose B-spline
        // reads across it) and every base.
        const std::vector<std::string> biquadratic = {"noise",
                                                      "spikes",
                                                      "cliffs",
                                                      "oblong300x77",
                                                      "tiny2x2",
                                                      "exrfloat",
                                                      "huge4096",
                                                      "cylinder_seam",
                                                      "sphere_seam",
                                                      "ellipsoid_cobbles",
                                                      "sphere_white",
                                                      "cylinder_spikes",
                                                      "sphere_oblong75x33",
                                                      "ellipsoid_single1x1"};
        for (const std::string& name : biquadratic) {
            const auto m = std::find_if(all.begin(), all.end(),
                                        [&](const SweepMapRecipe& r) { return r.name == name; });
            if (m == all.end()) throw std::logic_error("no sweep map named " + name);
            SweepMapRecipe copy = *m;
            copy.name += "_biquadratic";
            copy.interpolation = Interpolation::Biquadratic;
            all.push_back(std::move(copy));
        }
        return all;
    }();
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
            built.push_back({r.name, r.make(), r.heightScale, r.base, r.interpolation});
        return built;
    }();
    return maps;
}

namespace {

// Views of a curved base: orbits from high to grazing at several azimuths (the limb, rays
// tangent to the shell, rings every silhouette), the seam from behind (-z), the poles or
// the caps from above and below, grazing along the caps' plane and along the side, the
// eye inside the bounding shell but outside the solid, far away.
std::vector<SweepView> curvedViews(const SweepMap& m) {
    const HeightMap& map = *m.map;
    const BaseShape& base = m.base;
    const double top = m.heightScale * map.maxValue();
    const glm::dvec3 box = base.boxMax(map.width, map.height, top);
    const double size = std::max({box.x, box.y, box.z});
    std::vector<SweepView> views;
    const auto add = [&](const std::string& name, const Camera& camera) {
        views.push_back({name, camera});
    };
    for (double e : {60.0, 20.0, 3.0}) {
        for (double a : {15.0, 130.0, 250.0}) {
            add("e" + std::to_string(static_cast<int>(e)) + "a" +
                    std::to_string(static_cast<int>(a)),
                orbitCamera(e, a, 3.2 * size, {0.0, 0.0, 0.0}, 40.0));
        }
    }
    add("seam", orbitCamera(8.0, -90.0, 2.6 * size, {0.0, 0.0, 0.0}, 40.0));
    // Close up across the seam from its low side (columns 0, 1), looking at the slope up
    // to columns W - 2, W - 1: a pyramid that bounded the seam texels with clamped
    // neighbours would miss that slope here.
    add("top", orbitCamera(89.0, 30.0, 2.8 * size, {0.0, 0.0, 0.0}, 40.0));
    // The eye exactly on the axis: every ray's line meets the axis there, where every
    // half-plane of constant X meets it (base_curved.glsl: mr_curvedCrossX).
    Camera axis;
    axis.eye = {0.0, 2.8 * size, 0.0};
    axis.target = {0.0, 0.0, 0.0};
    axis.up = {0.0, 0.0, -1.0};
    axis.fovyDegrees = 40.0;
    add("axis", axis);
    add("bottom", orbitCamera(-89.0, 200.0, 2.8 * size, {0.0, 0.0, 0.0}, 40.0));
    const glm::dvec3 scale = base.frameScale();
    // A frame point at polar angle theta from +y and longitude phi, at radius r (for the
    // cylinder: height y, at distance r from the axis).
    const auto at = [&](double theta, double phi, double r, double y) {
        const glm::dvec3 q = base.kind == BaseKind::Cylinder
                                 ? glm::dvec3(r * std::sin(phi), y, r * std::cos(phi))
                                 : r * glm::dvec3(std::sin(theta) * std::sin(phi), std::cos(theta),
                                                  std::sin(theta) * std::cos(phi));
        return q * scale;
    };
    Camera seam;
    seam.eye = at(1.2, 3.14159265358979 + 0.12, 1.0 + top + 0.2, 0.3);
    seam.target = at(1.5, 3.14159265358979, 1.0, 0.0);
    seam.fovyDegrees = 15.0;
    add("seamclose", seam);
    Camera graze;
    graze.eye = at(1.2, 0.3, 1.0 + top + 0.04, 0.3);
    graze.target = at(1.5, 1.1, 1.0, -0.1);
    graze.fovyDegrees = 50.0;
    add("grazing", graze);
    if (base.kind == BaseKind::Cylinder) {
        // Level with the top cap, just above it: rays skim the cap's plane.
        Camera cap;
        cap.eye = {2.5 * size, 0.5 * base.length + 0.01, 0.3 * size};
        cap.target = {0.0, 0.5 * base.length - 0.01, 0.0};
        cap.fovyDegrees = 30.0;
        add("capgraze", cap);
    } else {
        // Low over the pole, looking across it.
        Camera pole;
        pole.eye = at(0.15, 2.0, 1.0 + top + 0.05, 0.0);
        pole.target = at(0.3, 2.0 + 3.14159, 1.0, 0.0);
        pole.fovyDegrees = 60.0;
        add("polegraze", pole);
    }
    // Inside the shell, above the lowest sample's point, halfway up to the shell.
    const auto lowest =
        std::min_element(map.samples.begin(), map.samples.end()) - map.samples.begin();
    const int i = static_cast<int>(lowest % map.width), j = static_cast<int>(lowest / map.width);
    const double hLow = m.heightScale * map.at(i, j);
    if (top > hLow) {
        const double phi = 2.0 * 3.14159265358979 * ((i + 0.5) / map.width - 0.5);
        const double v = (j + 0.5) / map.height;
        const double r = 1.0 + hLow + 0.5 * (top - hLow);
        Camera inside;
        inside.eye = at(3.14159265358979 * v, phi, r, 1.0 - 2.0 * v);
        inside.target = at(3.14159265358979 * v + 0.3, phi + 0.5, 1.0, 1.0 - 2.0 * v - 0.2);
        inside.fovyDegrees = 80.0;
        add("inside", inside);
    }
    add("far", orbitCamera(30.0, 75.0, 40.0 * size, {0.0, 0.0, 0.0}, 3.0));
    return views;
}

}  // namespace

std::vector<SweepView> sweepViews(const SweepMap& m) {
    if (m.base.curved()) return curvedViews(m);
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
