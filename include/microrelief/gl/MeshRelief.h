// The relief on a triangle mesh drawn by the GPU (docs/bases.md, "The mesh"; issue 50): the
// proxy (core/base/MeshProxy.h: each prism's hull, at most 8 triangles a mesh triangle,
// carrying its index) as a vertex buffer, the mesh's triangles as a texture, the map's samples
// and the windows of its pyramid repeated in u and v, and the program of shaders/
// mesh_relief.vert + mesh_relief.frag (microrelief/base_mesh.glsl: MeshTracer's traversal in
// GLSL). Each fragment traces its ray in its prism and writes the hit's depth; the depth test
// keeps the first over prisms.
//
// use:      MeshRelief relief(gl, shaderDirectory(), mesh, map, heightScale);   // defaults
//           MeshRelief relief(gl, shaderDirectory(), mesh, map, heightScale, options);
//           target.clear(background);                      // OffscreenTarget
//           relief.draw(viewProjection, eye);              // into the bound framebuffer
// options:  MeshReliefOptions: the last level (bilinear, biquadratic), the light's direction,
//           the albedo, the colour view (shaded, or the normal debug view).
//
// Drawn with the depth test (GL_LESS), back faces culled but for the hulls that may hold the
// eye (core/base/MeshProxy.h's hullsThatMayHold, per draw: an eye inside a hull sees only its
// back faces), which are drawn without culling: a ray crossing a hull from outside gets one
// fragment of it (where it enters), tracing that prism from the eye, rather than one a face
// it crosses (twice the fragments, each tracing the same prism); and with depth clamping on,
// so that a hull's faces nearer than the near plane (the eye inside the shell) are not
// clipped away (the hits before the near plane get depth 0).
//
// Outputs (relief.frag's locations, OffscreenTarget's attachments): 0 the colour, linear (an
// sRGB target encodes it while sRGB writes are on, gl::SrgbWrites): the library's shading
// (shaders/microrelief/shading.glsl, mr_shadeRelief, as relief.frag shades the analytic
// bases) of the albedo under one directional light at the hit's exact surface normal, no
// shadows; 1 the position AOV, the hit less `eye` (OffscreenTarget's), in the mesh's units;
// 2 the statistics (zero); 3 the light's share (1); and 4 the normal AOV, the hit's outward
// unit normal (x, y, z) and 1, for a target with a fifth draw buffer (OffscreenTarget has
// none yet: the GL drops it there). The normal is the exact surface's (MeshReference.h,
// MeshHit::normal), computed at the hit in float: the top t = h(uv(b)) from the derivatives of
// X(b, h(uv(b))) over the triangle (the map's gradient through uv(b)), the mesh itself at
// t = 0, a wall b_i = 0, a fold; zero where the eye is inside the solid. No model transform
// (the mesh's units are the world's). Not yet: shadows, an albedo map.
#pragma once

#include <filesystem>

#include <glm/glm.hpp>

#include "microrelief/core/base/MeshProxy.h"
#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Method.h"
#include "microrelief/gl/Objects.h"

namespace microrelief::gl {

struct MeshReliefOptions {
    // The last level (MICRORELIEF_INTERPOLATION): the bilinear cells between sample centres or
    // the biquadratic B-spline, as MeshTracer and MeshReference have them.
    Interpolation interpolation = Interpolation::Bilinear;
    // Towards the directional light (normalised when set; not zero), and the surface's diffuse
    // colour, linear: ShadingOptions' defaults (microrelief-render's).
    glm::vec3 lightDirection = ShadingOptions{}.lightDirection;
    glm::vec3 albedo = ShadingOptions{}.albedo;
    // The colour: DebugView::Shaded, or DebugView::Normal (n * 0.5 + 0.5, debug_views.glsl, as
    // microrelief-render's --view normal); the others are refused (Error(BadInput)).
    DebugView view = DebugView::Shaded;
};

class MeshRelief {
public:
    // `mesh` as io/MeshFile.h's loadMeshFile gives it (unit normals, no zero-area triangles),
    // `map` non-empty with finite heights >= 0, its row j at v = (j + 1/2) / H (bottom row
    // first, as OpenGL's textures: a map read from an image, top row first, is passed
    // rowsReversed, HeightMap.h), `heightScale` s >= 0 in the mesh's units.
    // Throws Error(BadInput) where the triangle table exceeds the GL's texture size,
    // Error(Runtime) where the program does not compile.
    MeshRelief(const GL& gl, const std::filesystem::path& shaderDir, const TriangleMesh& mesh,
               const HeightMap& map, double heightScale);
    // The same with `options` (MeshReliefOptions); Error(BadInput) also for a zero or
    // non-finite light direction and a view other than Shaded or Normal.
    MeshRelief(const GL& gl, const std::filesystem::path& shaderDir, const TriangleMesh& mesh,
               const HeightMap& map, double heightScale, const MeshReliefOptions& options);

    // Draws the relief into the bound framebuffer (its viewport), seen through
    // `viewProjection` (mesh units to clip space) from `eye` (mesh units). GL state is
    // restored after. The shader works about origin() (a far mesh's box centre): the eye and
    // the projection are moved there in double. A float viewProjection of a mesh far from the
    // file's origin has its translation rounded to float there (2^-24 of the distance: at
    // 1e5 units the hulls drawn up to 0.006 units off the rays the shader traces); pass the
    // double one.
    void draw(const glm::dmat4& viewProjection, const glm::dvec3& eye) const;
    void draw(const glm::mat4& viewProjection, const glm::dvec3& eye) const;

    // The pyramid's top H (map units): the prisms reach t in [0, H].
    float top() const { return top_; }
    int proxyTriangles() const { return proxyTriangles_; }
    // The proxy drawn (its hulls' float vertices, each mesh triangle's range of them), in the
    // mesh's units less origin().
    const MeshProxy& proxy() const { return proxy_; }
    // Where the shader's coordinates start: the middle of the vertices' box (a float) where
    // that is farther from zero than the box's diagonal, else zero.
    glm::dvec3 origin() const { return origin_; }

private:
    const GL& gl_;
    Program program_;
    VertexArray vertexArray_;
    Buffer positions_, indices_;
    Texture table_, heights_, windows_;
    MeshProxy proxy_;  // kept for hullsThatMayHold at each draw
    int proxyTriangles_ = 0, levelCount_ = 0;
    float top_ = 0.0f, heightScale_ = 0.0f;
    glm::vec2 mapSize_{0.0f};
    glm::dvec3 origin_{0.0};
    GLint viewProjection_ = -1, eye_ = -1;
};

}  // namespace microrelief::gl
