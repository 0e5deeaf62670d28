#include "OutputFiles.h"

#include <ctime>

namespace microrelief {

std::string localTimestamp() {
    const std::time_t t = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y%m%d-%H%M%S", std::localtime(&t));
    return text;
}

std::filesystem::path screenshotPath(const std::filesystem::path& folder,
                                     const std::string& stamp) {
    std::filesystem::path file = folder / ("viewer-" + stamp + ".png");
    for (int n = 2; std::filesystem::exists(file); ++n)
        file = folder / ("viewer-" + stamp + "-" + std::to_string(n) + ".png");
    return file;
}

std::string editedMapPath(const std::filesystem::path& mapFile, bool keepsGround) {
    return (std::filesystem::path("out") /
            (mapFile.stem().string() + (keepsGround ? "-edited.tif" : "-edited.exr")))
        .string();
}

}  // namespace microrelief
