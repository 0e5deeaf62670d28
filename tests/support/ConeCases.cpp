#include "ConeCases.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "microrelief/core/synth/SyntheticMaps.h"

namespace microrelief::test {

namespace {

HeightMap ramp(int w, int h, double slopeX, double slopeY) {
    HeightMap m(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) m.at(i, j) = static_cast<float>(slopeX * i + slopeY * j);
    return m;
}

HeightMap periodic(int w, int h, double period, double amplitude) {
    HeightMap m(w, h);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            m.at(i, j) =
                static_cast<float>(amplitude * (1.5 + std::sin(2 * M_PI * i / period) *
                                                          std::cos(2 * M_PI * j / period)));
    return m;
}

HeightMap scaled(HeightMap m, float factor) {
    for (float& s : m.samples) s *= factor;
    return m;
}

}  // namespace

std::vector<ConeCase> coneCases() {
    std::vector<ConeCase> cases;
    cases.push_back({"spike", synth::spike(13, 11, 6, 5)});
    cases.push_back({"spikeAtEdge", synth::spike(12, 12, 0, 11)});
    cases.push_back({"wall", synth::wallColumn(14, 9, 7)});
    cases.push_back({"step", synth::step(12, 10, 5)});
    cases.push_back({"ramp", ramp(11, 13, 0.07, 0.03)});
    cases.push_back({"steepRamp", ramp(10, 10, 1.0, 0.0)});
    cases.push_back({"periodic", periodic(16, 16, 5.0, 0.3)});
    cases.push_back({"white", synth::whiteNoise(16, 16, 7)});
    cases.push_back({"whiteTall", scaled(synth::whiteNoise(12, 14, 9), 1000.0f)});
    cases.push_back({"whiteLow", scaled(synth::whiteNoise(13, 12, 11), 0.001f)});
    cases.push_back({"noise", synth::valueNoise(16, 16, 4.0, 3, 5)});
    // Heights down to 1e-22 (a shift past a word in the half rounding, undefined in GLSL,
    // gave the GPU build apexes far above the surface there and wider cones) and 1e-9.
    HeightMap bump(20, 20);
    for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 20; ++i)
            bump.at(i, j) = static_cast<float>(
                std::exp(-((i - 9.5) * (i - 9.5) + (j - 9.5) * (j - 9.5)) / 4.0));
    cases.push_back({"gaussianTiny", bump});
    cases.push_back({"noiseTiny", scaled(synth::valueNoise(12, 12, 3.0, 3, 13), 1e-9f)});
    // A terrain: relief 3 high on a base 3000 high, where a float's rounding of h is large
    // beside h - B.
    HeightMap terrain = scaled(synth::valueNoise(16, 16, 4.0, 3, 17), 3.0f);
    for (float& sample : terrain.samples) sample += 3000.0f;
    cases.push_back({"terrainOffset", terrain});
    HeightMap pit = synth::flat(12, 12, 1.0f);
    pit.at(5, 6) = 0.0f;
    pit.at(6, 6) = 0.2f;
    cases.push_back({"pit", pit});
    std::mt19937 random(28);
    for (int k = 0; k < 4; ++k) {
        std::uniform_int_distribution<int> side(2, 15);
        HeightMap m(side(random), side(random));
        std::uniform_real_distribution<float> value(0.0f, 1.0f);
        std::bernoulli_distribution sparse(0.15);
        for (float& s : m.samples) s = sparse(random) ? value(random) : 0.0f;
        cases.push_back({"random" + std::to_string(k), m});
    }
    return cases;
}

void GpuConeMapCheck::add(const std::string& name, int width, const ConeMap& gpu,
                          const ConeMap& cpu) {
    if (gpu.ratio.size() != cpu.ratio.size() || gpu.apex.size() != cpu.apex.size()) {
        ++wrong;
        firstWrong.push_back(name + ": " + std::to_string(gpu.ratio.size()) + " texels, not " +
                             std::to_string(cpu.ratio.size()));
        return;
    }
    for (std::size_t k = 0; k < cpu.ratio.size(); ++k) {
        const bool apexSame = halfBits(gpu.apex[k]) == halfBits(cpu.apex[k]);
        if (!apexSame || !(gpu.ratio[k] <= cpu.ratio[k])) {
            if (++wrong <= 3) {
                std::ostringstream line;
                line << name << ", texel " << k % width << ", " << k / width << ": GPU ("
                     << gpu.apex[k] << ", " << gpu.ratio[k] << "), CPU (" << cpu.apex[k] << ", "
                     << cpu.ratio[k] << ")";
                firstWrong.push_back(line.str());
            }
        }
        same += gpu.ratio[k] == cpu.ratio[k];
        // Non-negative halves order as their bits do.
        mostHalvesBelow =
            std::max(mostHalvesBelow, int(halfBits(cpu.ratio[k])) - int(halfBits(gpu.ratio[k])));
    }
    texels += cpu.ratio.size();
}

std::string GpuConeMapCheck::summary() const {
    return std::to_string(same) + " of " + std::to_string(texels) + " ratios the CPU's, " +
           std::to_string(wrong) + " wider or off in the apex, at most " +
           std::to_string(mostHalvesBelow) + " halves narrower";
}

}  // namespace microrelief::test
