// The relief on a triangle mesh drawn by the GPU (docs/bases.md, "The mesh"; issue 50): the
// proxy (core/base/MeshProxy.h: each prism's hull, at most 8 triangles a mesh triangle,
// carrying its index) as a vertex buffer, the mesh's triangles as a texture, the map's samples
// and the windows of its pyramid repeated in u and v, and the program of shaders/
// mesh_relief.vert + mesh_relief.frag (microrelief/base_mesh.glsl: MeshTracer's traversal in
// GLSL). Each fragment traces its ray in its prism and writes the hit's depth; the depth test
// keeps the first over prisms.
//
// use:      MeshRelief relief(gl, shaderDirectory(), mesh, map, heightScale);
//           target.clear(background);                      // OffscreenTarget
//           relief.draw(viewProjection, eye);              // into the bound framebuffer
//
// Drawn with the depth test (GL_LESS) and no face culling: an eye inside a hull sees only its
// back faces (MeshProxy.h), and a ray crossing a hull gets one fragment a face it crosses,
// each tracing the same prism from the eye (the same hit, the depth test keeps one); and with
// depth clamping on, so that a hull's faces nearer than the near plane (the eye inside the
// shell) are not clipped away (the hits before the near plane get depth 0). The
// position AOV is the hit less `eye` (OffscreenTarget's), in the mesh's units; no model
// transform (the mesh's units are the world's). This slice: the bilinear last level, no
// shadows, no albedo; the colour is the hit's height in grey.
#pragma once

#include <filesystem>

#include <glm/glm.hpp>

#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/gl/Objects.h"

namespace microrelief::gl {

class MeshRelief {
public:
    // `mesh` as io/MeshFile.h's loadMeshFile gives it (unit normals, no zero-area triangles),
    // `map` non-empty with finite heights >= 0, `heightScale` s >= 0 in the mesh's units.
    // Throws Error(BadInput) where the triangle table exceeds the GL's texture size,
    // Error(Runtime) where the program does not compile.
    MeshRelief(const GL& gl, const std::filesystem::path& shaderDir, const TriangleMesh& mesh,
               const HeightMap& map, double heightScale);

    // Draws the relief into the bound framebuffer (its viewport), seen through
    // `viewProjection` (mesh units to clip space) from `eye` (mesh units). GL state is
    // restored after.
    void draw(const glm::mat4& viewProjection, const glm::dvec3& eye) const;

    // The pyramid's top H (map units): the prisms reach t in [0, H].
    float top() const { return top_; }
    int proxyTriangles() const { return proxyTriangles_; }

private:
    const GL& gl_;
    Program program_;
    VertexArray vertexArray_;
    Buffer positions_, indices_;
    Texture table_, heights_, windows_;
    int proxyTriangles_ = 0, levelCount_ = 0;
    float top_ = 0.0f, heightScale_ = 0.0f;
    glm::vec2 mapSize_{0.0f};
    GLint viewProjection_ = -1, eye_ = -1;
};

}  // namespace microrelief::gl
