// microrelief-make-map: writes one of the procedural height maps of synth/ as a 16-bit
// PNG (or any format by extension), and for cobbles and planet a matching albedo. The
// bundled assets/cobbles.png and assets/cobbles-albedo.png are
//   microrelief-make-map cobbles --size 256x256 --out assets/cobbles.png
//       --albedo assets/cobbles-albedo.png (one command)
#include <OpenImageIO/imageio.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "CommandLine.h"
#include "SceneOptions.h"
#include "microrelief/Version.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/synth/SyntheticMaps.h"
#include "microrelief/io/AlbedoFile.h"
#include "microrelief/io/ImageFile.h"

using namespace microrelief;

namespace {

// 8-bit sRGB for the integer formats, linear float for OpenEXR.
void writeAlbedo(ImageWriteBatch& batch, const std::filesystem::path& file,
                 const AlbedoImage& albedo) {
    const std::size_t pixels = static_cast<std::size_t>(albedo.width) * albedo.height;
    if (file.extension() == ".exr") {
        batch.write(file, {albedo.width,
                           albedo.height,
                           4,
                           PixelType::Float,
                           albedo.linear.data(),
                           {"R", "G", "B", "A"}});
        return;
    }
    std::vector<std::uint8_t> rgb(pixels * 3);
    for (std::size_t p = 0; p < pixels; ++p) {
        for (int c = 0; c < 3; ++c) {
            rgb[3 * p + c] = static_cast<std::uint8_t>(
                std::lround(linearToSrgb(albedo.linear[4 * p + c]) * 255.0f));
        }
    }
    batch.write(file, {albedo.width, albedo.height, 3, PixelType::UInt8, rgb.data(), {}});
}

// ", heights in 8 bits ..." where the format wrote the map's 16 bits as 8 (as the file's
// header says: BMP, JPEG, ...), else nothing: 256 levels make terraces a tracer shows.
std::string storedDepthNote(const std::string& file) {
    auto in = OIIO::ImageInput::open(file);
    if (!in) {
        OIIO::geterror();
        return "";
    }
    const bool shallow = in->spec().format.size() == 1;
    const bool lossy = std::string(in->format_name()) == "jpeg";
    in->close();
    return shallow ? std::string(", heights in 8 bits") + (lossy ? ", lossy" : "") +
                         ": .png or .tif keep 16, .exr float"
                   : "";
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Writes a procedural height map.", "microrelief-make-map"};
    std::string name = "cobbles", size = "256x256", out, albedoOut, albedoSize;
    std::uint32_t seed = 1;
    bool quiet = false;
    std::string known;
    for (const std::string& n : synth::names()) known += (known.empty() ? "" : ", ") + n;
    app.add_option("map", name, "Which map: " + known)->capture_default_str();
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--seed", seed, "Random seed")->capture_default_str();
    app.add_option("--out", out, "Output image (16-bit for PNG/TIFF, float for EXR)")->required();
    app.add_option("--albedo", albedoOut,
                   "Also write the map's colour texture here (cobbles and planet; 8-bit sRGB for "
                   "PNG, linear float for EXR)");
    app.add_option("--albedo-size", albedoSize,
                   "The albedo's WIDTHxHEIGHT (default: twice the map's; with --albedo)");
    app.add_flag("-q,--quiet", quiet, "Print nothing on success");
    app.set_version_flag("--version",
                         std::string("microrelief-make-map ") + MICRORELIEF_VERSION_STRING);
    if (const auto status = parseArgumentsOrExit(app, argc, argv, "microrelief-make-map"))
        return *status;
    try {
        int width = 0, height = 0;
        // No larger than a map the programs draw as one texture (kMaxHeightMapSide): at
        // the limit, 1 GiB of samples and 512 MiB of 16-bit words, made in memory.
        parseSizeFlag(size, width, height, kMaxHeightMapSide,
                      "the largest map this program makes (in memory, whole)");
        if (!albedoSize.empty() && albedoOut.empty())
            throwBadInput("--albedo-size needs --albedo FILE (the albedo to write)");
        int aw = 2 * width, ah = 2 * height;
        if (!albedoSize.empty()) {
            parseSizeFlag(albedoSize, aw, ah, kMaxAlbedoSide,
                          "the largest albedo microrelief loads", "--albedo-size");
        }
        // Before any work: formats, folders in the way, one file given twice.
        checkOutputTargets(albedoOut.empty() ? std::vector<std::filesystem::path>{out}
                                             : std::vector<std::filesystem::path>{out, albedoOut});
        const HeightMap map = synth::byName(name, width, height, seed);
        ImageWriteBatch batch;  // the map and its albedo: both or neither
        if (!albedoOut.empty()) {
            aw = std::min(aw, kMaxAlbedoSide);
            ah = std::min(ah, kMaxAlbedoSide);
            writeAlbedo(batch, albedoOut, synth::albedo(name, aw, ah, width, height, seed));
        }
        // Float for EXR; otherwise 16 bits, which PNG and TIFF store as they are.
        if (std::filesystem::path(out).extension() == ".exr") {
            batch.write(out, {width, height, 1, PixelType::Float, map.samples.data(), {"Y"}});
        } else {
            std::vector<std::uint16_t> words(map.samples.size());
            for (std::size_t k = 0; k < words.size(); ++k) {
                words[k] = static_cast<std::uint16_t>(
                    std::lround(std::clamp(map.samples[k], 0.0f, 1.0f) * 65535.0f));
            }
            batch.write(out, {width, height, 1, PixelType::UInt16, words.data(), {"Y"}});
        }
        batch.commit();
        if (!quiet) {
            std::cout << "microrelief-make-map: wrote " << out << " (" << name << ", " << width
                      << "x" << height << storedDepthNote(out) << ")"
                      << (albedoOut.empty() ? "" : " and " + albedoOut) << "\n";
        }
        return 0;
    } catch (const Error& e) {
        std::cerr << "microrelief-make-map: error: " << e.what() << '\n';
        return exitStatusOf(e.kind());
    } catch (const std::bad_alloc&) {
        std::cerr << "microrelief-make-map: error: " << out << ": not enough memory for a " << size
                  << " map\n";
        return 1;
    }
}
