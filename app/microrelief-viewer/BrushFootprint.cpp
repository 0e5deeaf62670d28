#include "BrushFootprint.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/type_ptr.hpp>

#include "microrelief/core/base/BaseType.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief {

std::vector<glm::vec3> footprintRing(const HeightMap& map, const BaseShape& base,
                                     Interpolation interpolation, double heightScale,
                                     const ModelTransform& model, const glm::dvec2& centre,
                                     double radius, int count) {
    std::vector<glm::vec3> ring;
    const double pi = 3.14159265358979323846;
    for (int k = 0; k < count; ++k) {
        const double angle = 2.0 * pi * k / count;
        glm::dvec2 p = centre + radius * glm::dvec2(std::cos(angle), std::sin(angle));
        // Round a curved base's axis the map wraps; elsewhere the ring keeps to the map.
        p.y = std::clamp(p.y, 0.0, static_cast<double>(map.height));
        p.x = base.wrapsU() ? p.x - map.width * std::floor(p.x / map.width)
                            : std::clamp(p.x, 0.0, static_cast<double>(map.width));
        const double h = map.surface(p.x, p.y, base.wrapsU(), interpolation);
        ring.push_back(glm::vec3(model.pointToWorld(
            baseType(base).objectPoint(base, map.width, map.height, heightScale, p, h))));
    }
    return ring;
}

BrushFootprint::BrushFootprint(const GL& gl, const std::filesystem::path& shaderDir) : gl_(gl) {
    const gl::Shader vertex = gl::compileShader(
        gl, GL_VERTEX_SHADER, assembleShader(shaderDir / "viewer" / "footprint.vert", "330 core"));
    const gl::Shader fragment =
        gl::compileShader(gl, GL_FRAGMENT_SHADER,
                          assembleShader(shaderDir / "viewer" / "footprint.frag", "330 core"));
    program_ = gl::linkProgram(gl, vertex, fragment, "brush footprint");
    viewProjection_ = gl::uniform(gl, program_, "viewProjection");
    colour_ = gl::uniform(gl, program_, "colour");
    vertexArray_ = gl::VertexArray::create(gl);
    vertices_ = gl::Buffer::create(gl);
}

void BrushFootprint::draw(const std::vector<glm::vec3>& ring, const glm::mat4& viewProjection,
                          const glm::vec3& eye, const glm::vec4& colour) {
    if (ring.size() < 2) return;
    std::vector<glm::vec3> nudged;
    for (const glm::vec3& p : ring) nudged.push_back(p + 1e-3f * (eye - p));
    const gl::StateGuard saved(gl_);
    GLboolean depthMask = GL_TRUE;
    gl_.GetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    gl_.UseProgram(program_.id());
    gl_.UniformMatrix4fv(viewProjection_, 1, GL_FALSE, glm::value_ptr(viewProjection));
    gl_.Uniform4fv(colour_, 1, glm::value_ptr(colour));
    gl_.BindVertexArray(vertexArray_.id());
    gl_.BindBuffer(GL_ARRAY_BUFFER, vertices_.id());
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(nudged.size() * sizeof(glm::vec3)),
                   nudged.data(), GL_STREAM_DRAW);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LEQUAL);
    gl_.DepthMask(GL_FALSE);
    gl_.Disable(GL_CULL_FACE);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE};
    gl_.DrawBuffers(3, buffers);
    gl_.DrawArrays(GL_LINE_LOOP, 0, static_cast<GLsizei>(nudged.size()));
    const GLenum all[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    gl_.DrawBuffers(3, all);
    gl_.DepthMask(depthMask);
}

}  // namespace microrelief
