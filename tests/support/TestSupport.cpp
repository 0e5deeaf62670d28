#include "TestSupport.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

namespace microrelief::test {

ScratchDir::ScratchDir() {
    std::random_device seed;
    std::mt19937_64 random(seed());
    path_ =
        std::filesystem::temp_directory_path() / ("microrelief-test-" + std::to_string(random()));
    std::filesystem::create_directories(path_);
}

ScratchDir::~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

void writeMap(const std::filesystem::path& file, const HeightMap& map, PixelType type) {
    std::vector<std::uint8_t> bytes;
    std::vector<std::uint16_t> words;
    const void* pixels = map.samples.data();
    if (type == PixelType::UInt8) {
        bytes.resize(map.samples.size());
        for (std::size_t k = 0; k < bytes.size(); ++k) {
            bytes[k] = static_cast<std::uint8_t>(
                std::lround(std::clamp(map.samples[k], 0.0f, 1.0f) * 255.0f));
        }
        pixels = bytes.data();
    } else if (type == PixelType::UInt16) {
        words.resize(map.samples.size());
        for (std::size_t k = 0; k < words.size(); ++k) {
            words[k] = static_cast<std::uint16_t>(
                std::lround(std::clamp(map.samples[k], 0.0f, 1.0f) * 65535.0f));
        }
        pixels = words.data();
    }
    writeImageAtomically(file, {map.width, map.height, 1, type, pixels, {"Y"}});
}

void writeBytes(const std::filesystem::path& file, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

std::vector<std::uint8_t> readBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string readText(const std::filesystem::path& file) {
    const std::vector<std::uint8_t> bytes = readBytes(file);
    return {bytes.begin(), bytes.end()};
}

int RunResult::errLines() const {
    return static_cast<int>(std::count(err.begin(), err.end(), '\n'));
}

RunResult runCommand(const std::string& command, const std::filesystem::path& scratch) {
    const std::filesystem::path out = scratch / "stdout", err = scratch / "stderr";
    const int raw = std::system((command + " > " + out.string() + " 2> " + err.string()).c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, readText(out), readText(err)};
}

void expectOneLineFailure(const RunResult& r, const std::string& program, int status,
                          const std::string& mentions) {
    EXPECT_EQ(r.status, status) << r.err;
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_EQ(r.err.rfind(program + ": error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos)
        << "expected '" << mentions << "' in: " << r.err;
}

Camera orbitCamera(double elevationDeg, double azimuthDeg, double distance, glm::dvec3 target,
                   double fovyDeg) {
    const double e = glm::radians(elevationDeg), a = glm::radians(azimuthDeg);
    Camera camera;
    camera.target = target;
    camera.eye = target + distance * glm::dvec3(std::cos(e) * std::cos(a), std::sin(e),
                                                std::cos(e) * std::sin(a));
    camera.fovyDegrees = fovyDeg;
    // Straight down: y is parallel to the view; take -z as up (the spec's top view).
    camera.up = elevationDeg > 89.999 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
    return camera;
}

bool missingBackendAllowed(Backend backend) {
    const char* list = std::getenv("MICRORELIEF_ALLOW_MISSING_GL");
    if (!list) return false;
    std::stringstream names(list);
    for (std::string name; std::getline(names, name, ',');) {
        if (name == "all" || name == backendName(backend)) return true;
    }
    return false;
}

std::string missingBackendMessage(Backend backend) {
    const std::string name = backendName(backend);
    return missingBackendAllowed(backend)
               ? "the " + name +
                     " backend is absent: skipped, as MICRORELIEF_ALLOW_MISSING_GL allows"
               : "the " + name +
                     " backend is absent: failing (set MICRORELIEF_ALLOW_MISSING_GL=" + name +
                     " to skip its tests instead)";
}

}  // namespace microrelief::test
