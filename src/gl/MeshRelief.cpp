#include "microrelief/gl/MeshRelief.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "microrelief/core/Error.h"
#include "microrelief/core/base/MeshProxy.h"
#include "microrelief/core/heightmap/MaxPyramid.h"
#include "microrelief/core/trace/MeshTracer.h"
#include "microrelief/core/trace/MultilevelTracer.h"
#include "microrelief/gl/ShaderProgram.h"
#include "microrelief/gl/ShaderSource.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief::gl {

namespace {

// base_mesh.glsl's MR_MESH_TABLE_ROW: triangles a row of the table, 8 texels each.
constexpr int kTableRow = 256;

void nearestTexture(const GL& gl, const Texture& texture, int maxLevel) {
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                     maxLevel > 0 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, maxLevel);
}

}  // namespace

MeshRelief::MeshRelief(const GL& gl, const std::filesystem::path& shaderDir,
                       const TriangleMesh& mesh, const HeightMap& map, double heightScale)
    : MeshRelief(gl, shaderDir, mesh, map, heightScale, MeshReliefOptions{}) {}

MeshRelief::MeshRelief(const GL& gl, const std::filesystem::path& shaderDir,
                       const TriangleMesh& mesh, const HeightMap& map, double heightScale,
                       const MeshReliefOptions& options)
    : gl_(gl) {
    if (map.empty()) throwBadInput("MeshRelief: an empty map");
    const glm::vec3 light = options.lightDirection;
    if (!std::isfinite(light.x) || !std::isfinite(light.y) || !std::isfinite(light.z) ||
        glm::dot(light, light) == 0.0f)
        throwBadInput("MeshRelief: the light's direction is zero or not finite");
    if (options.view != DebugView::Shaded && options.view != DebugView::Normal)
        throwBadInput(std::string("MeshRelief: the view ") + debugViewName(options.view) +
                      " is not drawn on a mesh (shaded or normal)");
    const std::string version = "330 core";
    const Shader vertex = compileShader(gl, GL_VERTEX_SHADER,
                                        assembleShader(shaderDir / "mesh_relief.vert", version));
    const std::vector<ShaderDefine> defines = {
        {"MICRORELIEF_INTERPOLATION", std::to_string(static_cast<int>(options.interpolation))}};
    const Shader fragment = compileShader(
        gl, GL_FRAGMENT_SHADER,
        assembleShader(shaderDir / "mesh_relief.frag", version, defines, {shaderDir}));
    program_ = linkProgram(gl, vertex, fragment, "mesh relief");
    viewProjection_ = uniform(gl, program_, "mr_viewProjection");
    eye_ = uniform(gl, program_, "mr_eye");

    const StateGuard saved(gl);
    // The pyramid of the map repeated in u and v, as MeshTracer reads it: the tile's windows,
    // the finest bounding each texel square with its wrapped neighbours (3 x 3 tiles, Half:
    // the grid the GPU's pyramids keep), held divided by 2^S (max_pyramid.glsl).
    const MaxPyramid pyramid(map, MapAddressing{false, 3, 3}, BoundPrecision::Half);
    top_ = std::max(pyramid.maxHeight(), 1e-6f);  // MeshTracer's top: a shell even over zeros
    heightScale_ = static_cast<float>(heightScale);
    mapSize_ = {static_cast<float>(map.width), static_cast<float>(map.height)};
    levelCount_ = pyramid.windowLevelCount();
    const float unscale = std::ldexp(1.0f, -pyramid.scaleExponent());

    windows_ = Texture::create(gl);
    nearestTexture(gl, windows_, levelCount_ - 1);
    for (int level = 0; level < levelCount_; ++level) {
        std::vector<float> texels = pyramid.windowLevelData(level);
        for (float& x : texels) x *= unscale;  // a power of two: exact
        gl.TexImage2D(GL_TEXTURE_2D, level, GL_R32F, pyramid.windowLevelWidth(level),
                      pyramid.windowLevelHeight(level), 0, GL_RED, GL_FLOAT, texels.data());
    }
    heights_ = Texture::create(gl);
    nearestTexture(gl, heights_, 0);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, map.width, map.height, 0, GL_RED, GL_FLOAT,
                  map.samples.data());

    // The mesh about its own origin (the middle of its vertices' box, a float): every float
    // the shader computes from positions (the ray's origin less a corner, the path's
    // coefficients) is then in the mesh's size rather than in its distance from the file's
    // origin, where a mesh at x = 1e5 kept 2^-7 of its units (a new-user review: 4.5 % of the
    // normals speckled at s = 0.01). p - origin is exact in double; rounded to float it moves
    // by at most 2^-25 of |p - origin|, the mesh's own float resolution at its size (and not
    // at all where the vertices share the origin's binade, as a mesh far from zero does: both
    // multiples of that ulp, their difference below 2^24 of it). The proxy and the table are
    // both built from these positions, so the hulls hold the prisms traced.
    glm::vec3 lo = mesh.positions.empty() ? glm::vec3(0.0f) : mesh.positions[0], hi = lo;
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    // Only a mesh farther from zero than its own size is moved: nearer, the floats gain little
    // and a host's float projection (draw(mat4, eye)) would be rounded once more (the CLI's
    // bumpy grid, its hits against the reference: 0.029 texel worst as drawn, 0.062 moved).
    const glm::dvec3 centre(glm::vec3(0.5f * lo + 0.5f * hi));
    origin_ = glm::length(centre) > glm::length(glm::dvec3(hi) - glm::dvec3(lo)) ? centre : glm::dvec3(0.0);
    TriangleMesh local = mesh;
    for (glm::vec3& p : local.positions) p = glm::vec3(glm::dvec3(p) - origin_);

    // The triangle table (base_mesh.glsl): 8 RGBA32F texels a triangle.
    proxy_ = buildMeshProxy(local, map, heightScale);
    const MeshProxy& proxy = proxy_;
    const int triangles = static_cast<int>(mesh.triangleCount());
    const int rows = (triangles + kTableRow - 1) / kTableRow;
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (rows > maxSize)
        throwBadInput("MeshRelief: " + std::to_string(triangles) + " triangles need a table of " +
                      std::to_string(rows) + " rows, more than the GL's texture size " +
                      std::to_string(maxSize));
    const std::vector<std::uint8_t> smooth = smoothEdges(mesh);
    std::vector<float> table(static_cast<std::size_t>(std::max(rows, 1)) * kTableRow * 8 * 4, 0.0f);
    for (int k = 0; k < triangles; ++k) {
        float* row = &table[static_cast<std::size_t>(k) * 8 * 4];
        const glm::uvec3 v = mesh.triangles[k];
        for (int i = 0; i < 3; ++i) {
            const glm::vec3 p = local.positions[v[i]], n = mesh.normals[v[i]];
            const glm::vec2 uv = mesh.texCoords[v[i]];
            float* a = row + 4 * i;
            float* m = row + 4 * (3 + i);
            const float corner[4] = {p.x, p.y, p.z, uv.x}, normal[4] = {n.x, n.y, n.z, uv.y};
            std::copy(corner, corner + 4, a);
            std::copy(normal, normal + 4, m);
        }
        row[4 * 6] = proxy.topHeights[k];
        row[4 * 6 + 1] = static_cast<float>(smooth[k]);  // 0..7: exact
    }
    table_ = Texture::create(gl);
    nearestTexture(gl, table_, 0);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kTableRow * 8, std::max(rows, 1), 0, GL_RGBA,
                  GL_FLOAT, table.data());

    // The proxy: positions and the flat mesh-triangle index a vertex.
    proxyTriangles_ = static_cast<int>(proxy.triangleCount());
    std::vector<std::uint32_t> index(proxy.positions.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = proxy.meshTriangles[i / 3];
    vertexArray_ = VertexArray::create(gl);
    gl.BindVertexArray(vertexArray_.id());
    positions_ = Buffer::create(gl);
    gl.BindBuffer(GL_ARRAY_BUFFER, positions_.id());
    gl.BufferData(GL_ARRAY_BUFFER,
                  static_cast<GLsizeiptr>(proxy.positions.size() * sizeof(glm::vec3)),
                  proxy.positions.data(), GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    indices_ = Buffer::create(gl);
    gl.BindBuffer(GL_ARRAY_BUFFER, indices_.id());
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(index.size() * sizeof(std::uint32_t)),
                  index.data(), GL_STATIC_DRAW);
    gl.EnableVertexAttribArray(1);
    gl.VertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
    gl.BindVertexArray(0);

    gl.UseProgram(program_.id());
    gl.Uniform1i(uniform(gl, program_, "mr_meshTable"), 0);
    gl.Uniform1i(uniform(gl, program_, "mr_meshHeights"), 1);
    gl.Uniform1i(uniform(gl, program_, "mr_meshWindows"), 2);
    gl.Uniform1f(uniform(gl, program_, "mr_heightScale"), heightScale_);
    gl.Uniform1f(uniform(gl, program_, "mr_top"), top_);
    gl.Uniform2f(uniform(gl, program_, "mr_mapSize"), mapSize_.x, mapSize_.y);
    gl.Uniform1i(uniform(gl, program_, "mr_levelCount"), levelCount_);
    gl.Uniform1i(uniform(gl, program_, "mr_budget"), traversalBudget(map.width, map.height));
    const glm::vec3 toLight = glm::normalize(light);
    gl.Uniform3f(uniform(gl, program_, "mr_lightDirection"), toLight.x, toLight.y, toLight.z);
    gl.Uniform3f(uniform(gl, program_, "mr_albedo"), options.albedo.r, options.albedo.g,
                 options.albedo.b);
    // DebugView's values are the MR_DEBUG_VIEW_* constants of debug_views.glsl (ReliefShader.cpp
    // asserts it).
    gl.Uniform1i(uniform(gl, program_, "mr_debugView"), static_cast<int>(options.view));
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("MeshRelief: GL error " + enumHex(error) + " uploading the mesh");
}

void MeshRelief::draw(const glm::mat4& viewProjection, const glm::dvec3& eye) const {
    draw(glm::dmat4(viewProjection), eye);
}

void MeshRelief::draw(const glm::dmat4& viewProjection, const glm::dvec3& eye) const {
    const StateGuard saved(gl_);
    gl_.UseProgram(program_.id());
    // The mesh's units less origin_ (the constructor): the eye and the projection moved in
    // double, so that the shader sees the eye in the mesh's size.
    const glm::mat4 localViewProjection(viewProjection * glm::translate(glm::dmat4(1.0), origin_));
    const glm::dvec3 localEye = eye - origin_;
    gl_.UniformMatrix4fv(viewProjection_, 1, GL_FALSE, &localViewProjection[0][0]);
    gl_.Uniform3f(eye_, static_cast<float>(localEye.x), static_cast<float>(localEye.y),
                  static_cast<float>(localEye.z));
    const GLuint units[3] = {table_.id(), heights_.id(), windows_.id()};
    for (int i = 0; i < 3; ++i) {
        gl_.ActiveTexture(GL_TEXTURE0 + i);
        gl_.BindTexture(GL_TEXTURE_2D, units[i]);
    }
    gl_.Enable(GL_DEPTH_TEST);
    gl_.DepthFunc(GL_LESS);
    // One fragment a hull for a ray from outside it: back faces culled. Exact: each hull is a
    // closed surface wound counter-clockwise seen from outside (MeshProxy.h), so at a pixel
    // whose ray passes through its interior (as every ray that meets the prism does: the
    // float hull encloses the exact one with a margin, MeshProxy.h), from an eye outside it,
    // the front faces rasterised over that pixel outnumber the back faces by the winding
    // number 1: at least one front-face fragment, which traces the prism from the eye as a
    // back face's would. An eye inside a hull sees none of its front faces: the hulls that
    // may hold the eye (hullsThatMayHold: the float vertices' box holds it, a superset) are
    // drawn without culling. Which winding is front follows the orientation of
    // viewProjection: a perspective camera's has a negative determinant (its clip z points
    // away from the eye) and keeps counter-clockwise counter-clockwise on screen; a mirrored
    // one (a positive determinant) turns it clockwise.
    gl_.CullFace(GL_BACK);
    gl_.FrontFace(glm::determinant(viewProjection) < 0.0 ? GL_CCW : GL_CW);
    // No clipping at the near plane: an eye inside a hull (inside the shell) may have that
    // hull's faces nearer than it, and its rays' hits may be too; clipped, the prism would
    // give no fragment and the pixel would show a later prism's hit. The clip volume's
    // -w <= x, y <= w still clips what lies behind the eye. Hits nearer than the near plane
    // get depth 0 (the shader clamps), so among those the first drawn is kept.
    gl_.Enable(GL_DEPTH_CLAMP);
    gl_.BindVertexArray(vertexArray_.id());
    const auto drawRange = [&](std::uint32_t first, std::uint32_t end, bool cull) {
        if (end <= first) return;
        if (cull) gl_.Enable(GL_CULL_FACE);
        else gl_.Disable(GL_CULL_FACE);
        gl_.DrawArrays(GL_TRIANGLES, static_cast<GLint>(3 * first),
                       static_cast<GLsizei>(3 * (end - first)));
    };
    std::uint32_t from = 0;
    // The eye as the shader has it (float), so that the hull holding it is named.
    for (const std::uint32_t k : hullsThatMayHold(proxy_, glm::dvec3(glm::vec3(localEye)))) {
        drawRange(from, proxy_.firstProxyTriangle[k], true);
        from = proxy_.firstProxyTriangle[k + 1];
        drawRange(proxy_.firstProxyTriangle[k], from, false);
    }
    drawRange(from, static_cast<std::uint32_t>(proxyTriangles_), true);
    gl_.BindVertexArray(0);
}

}  // namespace microrelief::gl
