// Albedo textures from image files, through OpenImageIO (the microrelief::io component).
#pragma once

#include <filesystem>

#include "microrelief/core/image/Albedo.h"

namespace microrelief {

// The largest albedo side: the GL_MAX_TEXTURE_SIZE that OpenGL 4.1 and later guarantee.
inline constexpr int kMaxAlbedoSide = 16384;

// Reads any image OpenImageIO can read, with the checks every input gets (a regular file,
// a size from the header within kMaxAlbedoSide before anything is allocated, a PNG that
// libpng would accept). Grey, grey and alpha, RGB and RGBA images are taken (the alpha is
// not used); 8-bit ones stay sRGB-encoded, 16-bit integer ones are decoded from sRGB to
// linear, float ones are linear already and must be finite (a NaN or an infinity is
// refused, naming the first such texel). Throws Error(BadInput) naming the file and the
// reason, Error(Runtime) naming it when memory runs out.
AlbedoImage loadAlbedo(const std::filesystem::path& file);

}  // namespace microrelief
