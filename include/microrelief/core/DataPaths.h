// Where the programs find their shaders and bundled assets, wherever they are started
// from: <folder of the executable>/../share/microrelief, the layout of both the build
// tree and an install. MICRORELIEF_DATA_DIR overrides it.
#pragma once

#include <filesystem>

namespace microrelief {

std::filesystem::path dataDirectory();
std::filesystem::path shaderDirectory();       // dataDirectory() / "shaders"
std::filesystem::path defaultHeightMapPath();  // the bundled default map
std::filesystem::path defaultAlbedoPath();     // its colours

}  // namespace microrelief
