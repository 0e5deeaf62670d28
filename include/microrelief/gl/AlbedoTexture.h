// An albedo on the GPU (image/Albedo.h): one 2D texture with its whole mip chain, 8-bit
// images as SRGB8_ALPHA8 (the GL decodes them before it filters), others as RGBA16F,
// filtered trilinearly and anisotropically where the GL can (up to 16 x), so that the
// shader's textureGrad, given the pixel's footprint at the hit, averages what the pixel
// covers. Repeating in both directions: the map's tiles and a curved base's seam continue
// it, and the plane's edges are clamped by the shader's coordinates.
#pragma once

#include "microrelief/gl/Objects.h"
#include "microrelief/image/Albedo.h"

namespace microrelief {

class AlbedoTexture {
public:
    // Throws Error(BadInput) beyond GL_MAX_TEXTURE_SIZE naming `source`. GL state restored.
    AlbedoTexture(const GL& gl, const AlbedoImage& image, const std::string& source);

    GLuint id() const { return texture_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    float maxAnisotropy() const { return anisotropy_; }

private:
    gl::Texture texture_;
    int width_ = 0, height_ = 0;
    float anisotropy_ = 1.0f;
};

}  // namespace microrelief
