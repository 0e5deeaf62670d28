#include "microrelief/core/DataPaths.h"

#include <cstdlib>
#include <mutex>

#include "microrelief/core/Error.h"

namespace microrelief {

namespace {
std::mutex chosenMutex;
std::filesystem::path chosen;  // setDataDirectory's; empty: none
}  // namespace

void setDataDirectory(const std::filesystem::path& folder) {
    if (!folder.empty()) {
        std::error_code ec;
        if (!std::filesystem::is_directory(folder / "shaders", ec)) {
            throwBadInput(folder.string() +
                          ": not the library's data folder (it holds no shaders/; an install's "
                          "share/microrelief does)");
        }
    }
    const std::lock_guard<std::mutex> lock(chosenMutex);
    chosen = folder;
}

std::filesystem::path dataDirectory() {
    if (const char* override = std::getenv("MICRORELIEF_DATA_DIR"); override && *override)
        return override;
    {
        const std::lock_guard<std::mutex> lock(chosenMutex);
        if (!chosen.empty()) return chosen;
    }
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throwRuntime("cannot locate the running program (/proc/self/exe): " + ec.message());
    const std::filesystem::path data = exe.parent_path().parent_path() / "share" / "microrelief";
    if (!std::filesystem::is_directory(data, ec)) {
        throwRuntime(data.string() +
                     ": the shader and asset folder is missing (a program outside the package's "
                     "prefix names it: setDataDirectory, or MICRORELIEF_DATA_DIR)");
    }
    return data;
}

std::filesystem::path shaderDirectory() {
    return dataDirectory() / "shaders";
}

std::filesystem::path defaultHeightMapPath() {
    return dataDirectory() / "assets" / "cobbles.png";
}

std::filesystem::path defaultAlbedoPath() {
    return dataDirectory() / "assets" / "cobbles-albedo.png";
}

}  // namespace microrelief
