#include "microrelief/gl/ShaderProgram.h"

#include <sstream>
#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/core/Log.h"

namespace microrelief::gl {

namespace {

const char* stageName(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        default:
            return "shader";
    }
}

std::string infoLog(const GL& gl, GLuint name, bool isProgram) {
    GLint length = 0;
    if (isProgram)
        gl.GetProgramiv(name, GL_INFO_LOG_LENGTH, &length);
    else
        gl.GetShaderiv(name, GL_INFO_LOG_LENGTH, &length);
    if (length <= 1) return {};
    std::vector<char> text(static_cast<std::size_t>(length));
    if (isProgram)
        gl.GetProgramInfoLog(name, length, nullptr, text.data());
    else
        gl.GetShaderInfoLog(name, length, nullptr, text.data());
    std::string log(text.data());
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
    return log;
}

// First line that reads like an error, and how many lines follow it: the one-line
// summary an exception carries. The whole log goes to the log sink first.
std::string summarise(const std::string& log) {
    std::istringstream lines(log);
    std::string line, first;
    int count = 0;
    while (std::getline(lines, line)) {
        if (line.empty()) continue;
        if (first.empty() ||
            (first.find("error") == std::string::npos && line.find("error") != std::string::npos)) {
            first = line;
        }
        ++count;
    }
    if (count > 1) first += " (+" + std::to_string(count - 1) + " more log lines)";
    return first;
}

}  // namespace

Shader compileShader(const GL& gl, GLenum stage, const ShaderSource& source) {
    Shader shader(gl, gl.CreateShader(stage));
    const char* text = source.text.c_str();
    gl.ShaderSource(shader.id(), 1, &text, nullptr);
    gl.CompileShader(shader.id());
    GLint ok = GL_FALSE;
    gl.GetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    const std::string log = mapCompilerLog(infoLog(gl, shader.id(), false), source.files);
    const std::string what =
        std::string(stageName(stage)) + " shader " +
        (source.files.empty() ? std::string("?") : source.files.front().string()) + " (GLSL " +
        source.version + ")";
    if (!ok) {
        logInfo("compile log of the " + what + ":\n" + log);
        throwRuntime("cannot compile the " + what + ": " + summarise(log));
    }
    if (!log.empty()) logWarning("the " + what + " compiled with messages:\n" + log);
    return shader;
}

Program linkProgram(const GL& gl, const Shader& vertex, const Shader& fragment,
                    const std::string& name) {
    Program program(gl, gl.CreateProgram());
    gl.AttachShader(program.id(), vertex.id());
    gl.AttachShader(program.id(), fragment.id());
    gl.LinkProgram(program.id());
    GLint ok = GL_FALSE;
    gl.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    const std::string log = infoLog(gl, program.id(), true);
    gl.DetachShader(program.id(), vertex.id());
    gl.DetachShader(program.id(), fragment.id());
    if (!ok) throwRuntime("cannot link the program " + name + ": " + summarise(log));
    if (!log.empty()) logWarning("the program " + name + " linked with messages:\n" + log);
    return program;
}

}  // namespace microrelief::gl
