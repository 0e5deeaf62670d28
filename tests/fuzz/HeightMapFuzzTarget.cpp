// The fuzz target of the height-map loading path: any bytes, as a file, through
// loadHeightMap, exactly as --height FILE reads them. Built two ways from this one file:
// with libFuzzer (clang, the `fuzz` preset, scripts/fuzz.sh) to search for inputs, and
// into the normal suite, where tests/fuzz/ReplayTest.cpp calls this same entry point on
// every file of the seed corpus (tests/fuzz/corpus).
//
// Beyond "no crash, no hang, no leak" (the sanitizers' part), it checks what the loader
// promises: a map within the stated limits whose samples are finite and >= 0, or one
// microrelief::Error whose message is a single line naming the file; and never a read
// that failed inside libpng, whose default handler prints its own stderr line under
// OpenImageIO 2.4 (src/io/PngCheck.h). Anything else aborts, which libFuzzer
// records as a crash with the input that caused it.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "microrelief/core/Error.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/io/HeightMapFile.h"

namespace {

[[noreturn]] void broken(const std::string& what) {
    std::fprintf(stderr, "height-map fuzz target: %s\n", what.c_str());
    std::abort();
}

// The file's extension, which picks the one reader the loader uses: from the bytes' magic
// number for PNG, OpenEXR and TIFF, the formats of the seeds; otherwise the first byte
// picks among other readers a height map might go to, so that a damaged or misnamed file
// meets them too.
const char* extensionFor(const std::uint8_t* data, std::size_t size) {
    auto starts = [&](const char* magic, std::size_t n) {
        return size >= n && std::memcmp(data, magic, n) == 0;
    };
    if (starts("\x89PNG", 4)) return ".png";
    if (starts("\x76\x2f\x31\x01", 4)) return ".exr";
    if (starts("II*\0", 4) || starts("MM\0*", 4)) return ".tif";
    static const char* const others[] = {".jpg", ".tga", ".bmp", ".hdr", ".pgm", ".psd", ".img"};
    return size == 0 ? ".img" : others[data[0] % std::size(others)];
}

std::filesystem::path scratchFolder() {
    // /dev/shm where there is one: the file is written and read for every input.
    std::filesystem::path base = "/dev/shm";
    if (!std::filesystem::is_directory(base)) base = std::filesystem::temp_directory_path();
    const std::filesystem::path folder = base / ("microrelief-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    return folder;
}

struct Scratch {
    std::filesystem::path folder = scratchFolder();
    ~Scratch() {
        std::error_code ignored;
        std::filesystem::remove_all(folder, ignored);
    }
};

// Smaller than the programs' limit (kMaxHeightMapSide), through the same check: an input
// whose header claims a large map costs at most 16 MiB of samples, not 1 GiB, and the
// fuzzer stays fast.
constexpr int kFuzzMaxSide = 2048;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const Scratch scratch;
    const std::filesystem::path file =
        scratch.folder / (std::string("input") + extensionFor(data, size));
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) broken("cannot write " + file.string());
    }
    try {
        microrelief::HeightMapLoadOptions options;
        options.maxSide = kFuzzMaxSide;
        const microrelief::HeightMap map = microrelief::loadHeightMap(file, options);
        if (map.width < 1 || map.height < 1 || map.width > kFuzzMaxSide ||
            map.height > kFuzzMaxSide ||
            map.samples.size() != static_cast<std::size_t>(map.width) * map.height)
            broken("a map of " + std::to_string(map.width) + " x " + std::to_string(map.height));
        for (float h : map.samples) {
            if (!(std::isfinite(h) && h >= 0.0f)) broken("a sample of " + std::to_string(h));
        }
    } catch (const microrelief::Error& e) {
        const std::string message = e.what();
        if (message.rfind(file.string() + ": ", 0) != 0) broken("unnamed error: " + message);
        if (message.find('\n') != std::string::npos)
            broken("a message of several lines: " + message);
        // OpenImageIO's PNG reader starts the message it records from libpng's error
        // callback so, and the loader puts it right after the file's name; anchored there,
        // since the fuzzer learns the text and writes it into other messages (an OpenEXR
        // attribute's name), which a search anywhere would take for libpng's.
        const std::string prefix = file.string() + ": cannot read the ";
        if (message.rfind(prefix + "image (PNG read error", 0) == 0 ||
            message.rfind(prefix + "pixels (PNG read error", 0) == 0)
            broken("libpng failed and printed its own line: " + message);
    }
    std::filesystem::remove(file);
    return 0;
}
