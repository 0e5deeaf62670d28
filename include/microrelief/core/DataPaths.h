// Where the library finds its shaders and bundled assets, wherever a program is started
// from: MICRORELIEF_DATA_DIR where it is set; else the folder the program named
// (setDataDirectory); else <folder of the executable>/../share/microrelief, the layout of
// both the build tree and an install (the project's own programs).
#pragma once

#include <filesystem>

namespace microrelief {

// The folder holding shaders/ and assets/ (an install's share/microrelief), for a program
// that does not live in the package's prefix (an engine's, built against the installed
// package): call it before anything loads shaders or the bundled map. An empty path goes
// back to the executable's folder. Throws Error(BadInput) for a path that is not a folder
// holding shaders/. Thread-safe.
void setDataDirectory(const std::filesystem::path& folder);

// The folder by the rule above; throws Error(Runtime) naming what it tried where none is.
std::filesystem::path dataDirectory();
std::filesystem::path shaderDirectory();       // dataDirectory() / "shaders"
std::filesystem::path defaultHeightMapPath();  // the bundled default map
std::filesystem::path defaultAlbedoPath();     // its colours

}  // namespace microrelief
