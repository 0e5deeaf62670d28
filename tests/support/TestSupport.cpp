#include "TestSupport.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
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

void writeWideWavesMap(const std::filesystem::path& file) {
    HeightMap map(17000, 40);
    for (int j = 0; j < map.height; ++j)
        for (int i = 0; i < map.width; ++i)
            map.at(i, j) = 0.5f + 0.4f * std::sin(i * 0.05f) * std::cos(j * 0.3f);
    writeMap(file, map, PixelType::UInt16);
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

RunResult runCommandWithFileSizeLimit(const std::string& command, std::uint64_t bytes) {
    // stdout and stderr through pipes, which the limit does not apply to: in files, the
    // error line itself would be cut at the limit.
    int out[2], err[2];
    if (::pipe(out) != 0) return {};
    if (::pipe(err) != 0) {
        ::close(out[0]);
        ::close(out[1]);
        return {};
    }
    const rlimit limit{static_cast<rlim_t>(bytes), static_cast<rlim_t>(bytes)};
    const pid_t pid = ::fork();
    if (pid == 0) {  // only async-signal-safe calls until exec
        ::dup2(out[1], 1);
        ::dup2(err[1], 2);
        for (int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
        ::signal(SIGXFSZ, SIG_IGN);
        ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::close(out[1]);
    ::close(err[1]);
    RunResult result;
    pollfd open[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
    std::string* text[2] = {&result.out, &result.err};
    for (int left = 2; left > 0 && pid > 0;) {
        if (::poll(open, 2, -1) < 0 && errno != EINTR) break;
        for (int k = 0; k < 2; ++k) {
            if (open[k].fd < 0 || open[k].revents == 0) continue;
            char buffer[4096];
            const ssize_t n = ::read(open[k].fd, buffer, sizeof buffer);
            if (n > 0) {
                text[k]->append(buffer, static_cast<std::size_t>(n));
            } else if (n == 0 || errno != EINTR) {
                ::close(open[k].fd);
                open[k].fd = -1;
                --left;
            }
        }
    }
    for (const pollfd& p : open)
        if (p.fd >= 0) ::close(p.fd);
    int raw = 0;
    if (pid < 0 || ::waitpid(pid, &raw, 0) != pid) return result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return result;
}

std::vector<std::string> hiddenFilesIn(const std::filesystem::path& folder) {
    std::vector<std::string> hidden;
    std::error_code ec;
    for (auto it = std::filesystem::directory_iterator(folder, ec);
         !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name[0] == '.') hidden.push_back(name);
    }
    std::sort(hidden.begin(), hidden.end());
    return hidden;
}

void expectOneLineFailure(const RunResult& r, const std::string& program, int status,
                          const std::string& mentions) {
    EXPECT_EQ(r.status, status) << r.err;
    EXPECT_EQ(r.errLines(), 1) << r.err;
    EXPECT_EQ(r.err.rfind(program + ": error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(mentions), std::string::npos)
        << "expected '" << mentions << "' in: " << r.err;
}

ReliefDesc relief(const BaseShape& base, Interpolation interpolation, float heightScale,
                  glm::ivec2 tiles) {
    ReliefDesc r;
    r.base = base;
    r.interpolation = interpolation;
    r.heightScale = heightScale;
    r.tiles = tiles;
    return r;
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

Image readImage(const std::filesystem::path& file) {
    Image image;
    auto in = OIIO::ImageInput::open(file.string());
    if (!in) return image;
    image.width = in->spec().width;
    image.height = in->spec().height;
    image.channels = in->spec().nchannels;
    image.pixels.resize(static_cast<std::size_t>(image.width) * image.height * image.channels);
    in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::UINT8, image.pixels.data());
    return image;
}

Aov readAov(const std::filesystem::path& file) {
    Aov aov;
    auto input = OIIO::ImageInput::open(file.string());
    if (!input) return aov;
    aov.width = input->spec().width;
    aov.height = input->spec().height;
    aov.pixels.resize(static_cast<std::size_t>(aov.width) * aov.height * 4);
    if (!input->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, aov.pixels.data())) return {};
    return aov;
}

Difference difference(const Image& a, const Image& b, int x0, int y0, int x1, int y1) {
    Difference d;
    double sum = 0.0;
    for (int row = y0; row < y1; ++row) {
        for (int column = x0; column < x1; ++column) {
            for (int c = 0; c < 3; ++c) {
                const int delta = std::abs(a.at(column, row, c) - b.at(column, row, c));
                d.max = std::max(d.max, delta);
                d.overOne += delta > 1;
                sum += delta;
            }
        }
    }
    d.mean = sum / (3.0 * (x1 - x0) * (y1 - y0));
    return d;
}

std::string keepForInspection(const std::string& folderName, const std::string& name,
                              const Image& actual, const Image& expected) {
    const std::filesystem::path folder = std::filesystem::current_path() / folderName;
    std::filesystem::create_directories(folder);
    Image diff = actual;
    for (std::size_t k = 0; k < diff.pixels.size() && k < expected.pixels.size(); ++k) {
        diff.pixels[k] = static_cast<std::uint8_t>(
            std::min(255, 8 * std::abs(actual.pixels[k] - expected.pixels[k])));
    }
    for (const auto& [suffix, image] :
         {std::pair{"actual", &actual}, {"expected", &expected}, {"diff", &diff}}) {
        writeImageAtomically(folder / (name + "-" + suffix + ".png"), {image->width,
                                                                       image->height,
                                                                       image->channels,
                                                                       PixelType::UInt8,
                                                                       image->pixels.data(),
                                                                       {}});
    }
    return (folder / (name + "-{actual,expected,diff}.png")).string();
}

RenderedFrame withWorldPositions(RenderedFrame frame) {
    for (std::size_t p = 0; p + 3 < frame.position.size(); p += 4) {
        if (frame.position[p + 3] < 0.5f) continue;
        for (int c = 0; c < 3; ++c)
            frame.position[p + c] = static_cast<float>(frame.positionOrigin[c] + frame.position[p + c]);
    }
    frame.positionOrigin = glm::dvec3(0.0);
    return frame;
}

double meshTexelSize(const TriangleMesh& mesh, const HeightMap& map, std::size_t k) {
    const glm::uvec3 v = mesh.triangles[k];
    const glm::dvec3 p0 = mesh.positions[v[0]], p1 = mesh.positions[v[1]],
                     p2 = mesh.positions[v[2]];
    const glm::dvec2 t0 = mesh.texCoords[v[0]], t1 = mesh.texCoords[v[1]],
                     t2 = mesh.texCoords[v[2]];
    const double world = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
    const glm::dvec2 a = (t1 - t0) * glm::dvec2(map.width, map.height),
                     b = (t2 - t0) * glm::dvec2(map.width, map.height);
    const double texels = 0.5 * std::abs(a.x * b.y - a.y * b.x);
    return std::sqrt(world / texels);
}

}  // namespace microrelief::test
