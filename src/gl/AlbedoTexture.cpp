#include "microrelief/gl/AlbedoTexture.h"

#include <algorithm>
#include <string>

#include "microrelief/core/Error.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief {

AlbedoTexture::AlbedoTexture(const GL& gl, const AlbedoImage& image, const std::string& source)
    : width_(image.width), height_(image.height) {
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (image.width > maxSize || image.height > maxSize) {
        throwBadInput(
            source + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
            " is larger than this GPU's GL_MAX_TEXTURE_SIZE (" + std::to_string(maxSize) + ")");
    }
    texture_ = gl::Texture::create(gl);
    const gl::StateGuard saved(gl);
    gl.BindTexture(GL_TEXTURE_2D, texture_.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    if (image.srgb8) {
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, image.width, image.height, 0, GL_RGBA,
                      GL_UNSIGNED_BYTE, image.bytes.data());
    } else {
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, image.width, image.height, 0, GL_RGBA, GL_FLOAT,
                      image.linear.data());
    }
    gl.GenerateMipmap(GL_TEXTURE_2D);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

}  // namespace microrelief
