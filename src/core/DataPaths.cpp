#include "microrelief/core/DataPaths.h"

#include <cstdlib>

#include "microrelief/core/Error.h"

namespace microrelief {

std::filesystem::path dataDirectory() {
    if (const char* override = std::getenv("MICRORELIEF_DATA_DIR"); override && *override)
        return override;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) throwRuntime("cannot locate the running program (/proc/self/exe): " + ec.message());
    const std::filesystem::path data = exe.parent_path().parent_path() / "share" / "microrelief";
    if (!std::filesystem::is_directory(data, ec)) {
        throwRuntime(data.string() +
                     ": the shader and asset folder is missing (set MICRORELIEF_DATA_DIR)");
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
