// The sculpting brush's footprint shown on the relief under the cursor: a ring of the
// brush's radius round the map point it would paint, each point lifted onto the surface
// the CPU mirror of the map holds (h there, over the base: core/base/BaseShape.h), placed by the
// model transform, and drawn as a line loop into the view's picture with the relief's
// depth (shaders/viewer/footprint.*), so the relief in front of it hides it.
#pragma once

#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/gl/Objects.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/ModelTransform.h"

namespace microrelief {

// The ring's world points: `count` points on the circle of `radius` texels round `centre`
// (map texels), on `map`'s surface.
std::vector<glm::vec3> footprintRing(const HeightMap& map, const BaseShape& base,
                                     Interpolation interpolation, double heightScale,
                                     const ModelTransform& model, const glm::dvec2& centre,
                                     double radius, int count = 96);

class BrushFootprint {
public:
    // Compiles shaders/viewer/footprint.* from `shaderDir`. Throws Error(Runtime).
    BrushFootprint(const GL& gl, const std::filesystem::path& shaderDir);

    // Draws `ring` (a closed loop, world) into the bound framebuffer's first colour output,
    // depth-tested against its depth (not written), nudged towards `eye` by a thousandth of
    // the distance so that the surface it lies on does not hide it. Restores the GL state.
    void draw(const std::vector<glm::vec3>& ring, const glm::mat4& viewProjection,
              const glm::vec3& eye, const glm::vec4& colour);

private:
    const GL& gl_;
    gl::Program program_;
    GLint viewProjection_ = -1, colour_ = -1;
    gl::VertexArray vertexArray_;
    gl::Buffer vertices_;
};

}  // namespace microrelief
