// Compiling and linking with the logs read every time (Magnum checkCompile, ImGui
// CheckShader): a failure throws Error(Runtime) whose one-line message names the stage,
// the file and line, and the GLSL version; a non-empty log on success is a warning.
#pragma once

#include <string>

#include "microrelief/gl/Objects.h"
#include "microrelief/gl/ShaderSource.h"

namespace microrelief::gl {

Shader compileShader(const GL& gl, GLenum stage, const ShaderSource& source);
Program linkProgram(const GL& gl, const Shader& vertex, const Shader& fragment,
                    const std::string& name);

// A uniform's location, or -1 when the linker dropped it (unused): setting -1 is a no-op.
inline GLint uniform(const GL& gl, const Program& program, const char* name) {
    return gl.GetUniformLocation(program.id(), name);
}

}  // namespace microrelief::gl
