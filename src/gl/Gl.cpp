#include "microrelief/gl/Gl.h"

#include <cstdio>

#include "microrelief/core/Error.h"

namespace microrelief::gl {

std::string enumHex(GLenum value) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%04X", static_cast<unsigned>(value));
    return text;
}

void refuseEarlierError(const GL& gl, const std::string& what) {
    if (const GLenum earlier = gl.GetError(); earlier != GL_NO_ERROR) {
        throwRuntime("GL error " + enumHex(earlier) +
                     " left by an earlier call on this context, before " + what);
    }
}

}  // namespace microrelief::gl
