// relief-headless: renders a height map with microrelief from a program of your own.
// The library builds the max pyramid and uploads it (ReliefTextures), assembles this
// example's fragment shader with the library's GLSL (assembleShader), and makes a
// headless context; the drawing is the program's: a full-screen triangle, its uniforms.
//
//   relief-headless [--height FILE] [--eye x,y,z] [--target x,y,z] [--fovy DEG]
//                   [--size WxH] [--out FILE]
#include <cstdio>
#include <sstream>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "microrelief/core/base/ReliefExtent.h"
#include "microrelief/headless/HeadlessContext.h"
#include "microrelief/core/Error.h"
#include "microrelief/gl/ReliefTextures.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"
#include "microrelief/io/HeightMapFile.h"
#include "microrelief/io/ImageFile.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/gl/OffscreenTarget.h"

using namespace microrelief;

namespace {

struct Options {
    std::string height = MICRORELIEF_BUNDLED_MAP, out = "relief.png";
    Camera camera;  // microrelief-render's default view
    int width = 1280, height_ = 720;
};

glm::dvec3 parseVector(const std::string& flag, const std::string& text) {
    glm::dvec3 v;
    char comma1 = 0, comma2 = 0;
    std::istringstream in(text);
    if (!(in >> v.x >> comma1 >> v.y >> comma2 >> v.z) || comma1 != ',' || comma2 != ',' ||
        !in.eof())
        throwBadInput(flag + " expects x,y,z, got '" + text + "'");
    return v;
}

Options parse(int argc, char** argv) {
    Options o;
    for (int k = 1; k < argc; ++k) {
        const std::string flag = argv[k];
        if (k + 1 >= argc) throwBadInput(flag + ": a value is missing");
        const std::string value = argv[++k];
        if (flag == "--height") o.height = value;
        else if (flag == "--out") o.out = value;
        else if (flag == "--eye") o.camera.eye = parseVector(flag, value);
        else if (flag == "--target") o.camera.target = parseVector(flag, value);
        else if (flag == "--fovy") o.camera.fovyDegrees = std::stod(value);
        else if (flag == "--size") {
            if (std::sscanf(value.c_str(), "%dx%d", &o.width, &o.height_) != 2 || o.width < 1 ||
                o.height_ < 1)
                throwBadInput("--size expects WIDTHxHEIGHT, got '" + value + "'");
        } else throwBadInput("unknown option " + flag);
    }
    return o;
}

// A triangle that covers the viewport, from gl_VertexID alone (no vertex buffer).
const char* const kFullScreenTriangle =
    "#version 330 core\n"
    "void main() { vec2 p = vec2(gl_VertexID & 1, gl_VertexID >> 1);\n"
    "              gl_Position = vec4(4.0 * p - 1.0, 0.0, 1.0); }\n";

int run(const Options& o) {
    const HeightMap map = loadHeightMap(o.height);
    const float heightScale = 0.1f;
    const auto context = createHeadlessContext(Backend::Auto);
    const GL& gl = context->gl();

    const ReliefTextures textures(gl, map, o.height, /*wrapU=*/false);
    const gl::Shader vertex =
        gl::compileShader(gl, GL_VERTEX_SHADER, {kFullScreenTriangle, {}, "330 core"});
    const gl::Shader fragment = gl::compileShader(
        gl, GL_FRAGMENT_SHADER,
        assembleShader(EXAMPLE_SHADER, "330 core", {}, {MICRORELIEF_SHADER_DIR}));
    const gl::Program program = gl::linkProgram(gl, vertex, fragment, "relief example");
    const gl::VertexArray noVertices = gl::VertexArray::create(gl);

    const CameraFrame camera = resolveCamera(o.camera, o.width, o.height_,
                                             sceneRadius(reliefExtent(map, heightScale)));
    OffscreenTarget target(gl, o.width, o.height_);  // sRGB colour: linear in, encoded out
    target.clear({0.11f, 0.12f, 0.14f});
    {
        const gl::SrgbWrites srgb(gl);
        auto uniform = [&](const char* name) { return gl::uniform(gl, program, name); };
        const ReliefMapShape& shape = textures.shape();
        gl.UseProgram(program.id());
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, textures.windowPyramid());
        gl.ActiveTexture(GL_TEXTURE1);
        gl.BindTexture(GL_TEXTURE_2D, textures.samples());
        gl.Uniform1i(uniform("windows"), 0);
        gl.Uniform1i(uniform("heights"), 1);
        gl.Uniform2f(uniform("mapSize"), float(shape.size.x), float(shape.size.y));
        gl.Uniform2i(uniform("pyramidSize"), shape.pyramidSize.x, shape.pyramidSize.y);
        gl.Uniform1i(uniform("levelCount"), shape.levelCount);
        gl.Uniform1f(uniform("maxHeight"), shape.maxHeight);
        gl.Uniform1f(uniform("heightScale"), heightScale);
        gl.Uniform3fv(uniform("eye"), 1, glm::value_ptr(glm::vec3(camera.eye)));
        gl.Uniform3fv(uniform("right"), 1, glm::value_ptr(glm::vec3(camera.right)));
        gl.Uniform3fv(uniform("up"), 1, glm::value_ptr(glm::vec3(camera.up)));
        gl.Uniform3fv(uniform("forward"), 1, glm::value_ptr(glm::vec3(camera.forward)));
        gl.Uniform2f(uniform("viewport"), float(o.width), float(o.height_));
        const glm::vec3 light = glm::normalize(glm::vec3(-0.45f, 0.8f, -0.35f));
        gl.Uniform3fv(uniform("lightDirection"), 1, glm::value_ptr(light));
        gl.Uniform3f(uniform("albedo"), 0.60f, 0.58f, 0.55f);
        gl.BindVertexArray(noVertices.id());
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
    }
    // This shader gets the eye as it is, so its positions are the world's (origin 0); a
    // ReliefRenderer's draw writes them about the eye: read(camera.eye) then.
    const RenderedFrame frame = target.read(glm::dvec3(0.0));
    const std::vector<std::uint8_t> rgb = rgbFromRgba(frame.color, frame.width, frame.height);
    writeImageAtomically(o.out, {frame.width, frame.height, 3, PixelType::UInt8, rgb.data(), {}});
    std::printf("relief-headless: wrote %s (%dx%d, %s)\n", o.out.c_str(), o.width, o.height_,
                context->renderer().c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(parse(argc, argv));
    } catch (const Error& e) {
        std::fprintf(stderr, "relief-headless: error: %s\n", e.what());
        return exitStatusOf(e.kind());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "relief-headless: error: %s\n", e.what());
        return 1;
    }
}
