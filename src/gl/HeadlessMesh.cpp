// HeadlessRenderer on the mesh base (gl/HeadlessRender.h: setMesh, render of a job with
// ReliefDesc::onMesh): the relief drawn by gl::MeshRelief into the renderer's OffscreenTarget,
// kept from one picture to the next while what it was built from stays the same; and the
// mesh's shell box and default camera.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"
#include "microrelief/core/Text.h"
#include "microrelief/core/scene/FloatLimits.h"
#include "microrelief/gl/HeadlessRender.h"
#include "microrelief/gl/MeshRelief.h"
#include "microrelief/gl/StateGuard.h"

namespace microrelief {

namespace {

// The clip-space crop that takes the tile `part` of a width x height picture (GL window
// coordinates, lower-left corner (part.x, part.y)) to the whole of a part.width x
// part.height viewport: x' = sx x + ox w (and y alike), z and w unchanged, so that each of
// the tile's pixels is the picture's pixel at the same place. MeshRelief traces the ray from
// the eye through the fragment's point on the hull (mesh_relief.frag), which the crop does not
// move, and writes the depth z / w, which it leaves alone.
glm::dmat4 tileCrop(const PictureTile& part, int width, int height) {
    glm::dmat4 crop(1.0);
    crop[0][0] = static_cast<double>(width) / part.width;
    crop[1][1] = static_cast<double>(height) / part.height;
    // NDC -1 + 2 part.x / width goes to -1, -1 + 2 (part.x + part.width) / width to 1.
    crop[3][0] = static_cast<double>(width - 2 * part.x - part.width) / part.width;
    crop[3][1] = static_cast<double>(height - 2 * part.y - part.height) / part.height;
    return crop;
}

}  // namespace

// setMesh's triangles and map, and the MeshRelief built from them with `built`'s values.
struct HeadlessRenderer::MeshState {
    std::shared_ptr<const TriangleMesh> mesh;
    std::shared_ptr<const HeightMap> map;
    std::string source;
    std::optional<gl::MeshRelief> relief;
    // What `relief` was built with (it bakes them in: MeshRelief's constructor).
    struct Key {
        double heightScale = 0.0;
        gl::MeshReliefOptions options;
        bool operator==(const Key& o) const {
            return heightScale == o.heightScale &&
                   options.interpolation == o.options.interpolation &&
                   options.lightDirection == o.options.lightDirection &&
                   options.albedo == o.options.albedo && options.view == o.options.view;
        }
    };
    Key built;
};

void HeadlessRenderer::setMesh(std::shared_ptr<const TriangleMesh> mesh,
                               std::shared_ptr<const HeightMap> map, const std::string& source) {
    if (!mesh || !map) throwRuntime("HeadlessRenderer::setMesh: no mesh or no map");
    if (mesh_ && mesh_->mesh == mesh && mesh_->map == map) return;  // its relief kept
    mesh_ = std::make_shared<MeshState>();
    mesh_->mesh = std::move(mesh);
    mesh_->map = std::move(map);
    mesh_->source = source;
}

HeadlessResult HeadlessRenderer::renderMesh(const RenderJob& job) {
    if (!mesh_) throwRuntime("HeadlessRenderer::render: a job on the mesh base and no mesh (setMesh)");
    // Before any GL work: the float range and precision the shader needs.
    checkMeshFloatLimits(*mesh_->mesh, *mesh_->map, job.heightScale, mesh_->source);
    context_.makeCurrent();
    const GL& gl = context_.gl();
    gl::refuseEarlierError(gl, "rendering " + mesh_->source);
    // Tiles as render() draws them (no larger than the GL's viewport and renderbuffer limits,
    // and maxTileSide_), each with the picture's viewProjection cropped to it (tileCrop).
    GLint maxRenderbuffer = 0, maxTexture = 0, maxViewport[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, maxViewport);
    const int tile = std::min({maxTileSide_, static_cast<int>(maxRenderbuffer),
                               static_cast<int>(maxTexture), static_cast<int>(maxViewport[0]),
                               static_cast<int>(maxViewport[1])});
    if (tile < 1) throwRuntime("the GL reports no usable framebuffer size (a failed query)");

    MeshState::Key key;
    key.heightScale = job.heightScale;
    key.options.interpolation = job.interpolation;
    key.options.lightDirection = glm::normalize(job.shading.lightDirection);
    key.options.albedo = job.shading.albedo;
    key.options.view = job.shading.view;
    if (!mesh_->relief || !(mesh_->built == key)) {
        mesh_->relief.reset();
        // The map's rows reversed (HeightMap.h: rowsReversed): the mesh's (0, 0) is the
        // image's bottom-left corner, as the contract has it, not its first row.
        mesh_->relief.emplace(gl, shaderDirectory(), *mesh_->mesh, rowsReversed(*mesh_->map),
                              key.heightScale, key.options);
        mesh_->built = key;
    }
    const gl::MeshRelief& relief = *mesh_->relief;

    // The depth range about the shell (meshShellExtent: every point of it in that box).
    const ReliefExtent shell = meshShellExtent(*mesh_->mesh, job.heightScale, relief.top());
    const CameraFrame camera =
        resolveCamera(job.camera, job.width, job.height, 0.5 * glm::length(shell.max - shell.min),
                      0.5 * (shell.min + shell.max));

    const int targetWidth = std::min(tile, job.width), targetHeight = std::min(tile, job.height);
    if (!target_ || target_->width() != targetWidth || target_->height() != targetHeight) {
        target_.reset();
        target_.emplace(gl, targetWidth, targetHeight);
    }
    HeadlessResult result{{}, camera, std::nullopt, {}};
    allocateFrame(result.frame, job, camera.eye);  // MeshRelief writes the hit less the eye
    for (int y = 0; y < job.height; y += tile) {
        for (int x = 0; x < job.width; x += tile) {
            const PictureTile part{x, y, std::min(tile, job.width - x),
                                   std::min(tile, job.height - y)};
            target_->clear(job.background);  // depth 1: MeshRelief's test is GL_LESS
            gl.Viewport(0, 0, part.width, part.height);
            {
                const gl::SrgbWrites srgb(gl);  // the relief's linear colour, encoded
                // The double projection: MeshRelief moves it to its origin() in double (a
                // float one far from the file's origin is rounded there: gl/MeshRelief.h).
                relief.draw(tileCrop(part, job.width, job.height) * camera.viewProjection,
                            camera.eye);
            }
            target_->readInto(result.frame, part.x, part.y, part.width, part.height);
        }
    }
    gl.Finish();
    const GLenum error = gl.GetError();
    if (error != GL_NO_ERROR)
        throwRuntime("GL error " + gl::enumHex(error) + " while rendering " + mesh_->source);
    return result;
}

namespace {

std::string figure(double value) { return formatNumber(value, 3); }

}  // namespace

MeshSize meshSize(const TriangleMesh& mesh) {
    MeshSize size;
    if (mesh.positions.empty()) return size;
    size.low = size.high = glm::dvec3(mesh.positions.front());
    for (const glm::vec3& p : mesh.positions) {
        size.low = glm::min(size.low, glm::dvec3(p));
        size.high = glm::max(size.high, glm::dvec3(p));
        size.reach = std::max({size.reach, std::abs(double(p.x)), std::abs(double(p.y)),
                               std::abs(double(p.z))});
    }
    size.diagonal = glm::length(size.high - size.low);
    std::vector<double> sides;
    sides.reserve(mesh.triangleCount());
    for (const glm::uvec3& v : mesh.triangles) {
        const glm::dvec3 p0 = mesh.positions[v[0]], p1 = mesh.positions[v[1]],
                         p2 = mesh.positions[v[2]];
        sides.push_back(std::sqrt(glm::length(glm::cross(p1 - p0, p2 - p0))));  // sqrt(2 area)
    }
    if (!sides.empty()) {
        std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
        size.medianTriangle = sides[sides.size() / 2];
    }
    return size;
}

// The limits, and why each holds (measured with microrelief-render on llvmpipe against
// core/trace/MeshReference.h, the exact reference, pixel by pixel, on a 4 x 4 and a 16 x 16
// quad grid of leaning normals, one unit wide, under a 64 x 32 noise map laid twice over it
// (a texel 0.011 units), 64 x 48 pixels; the thresholds are 0.1 % hit/miss and
// 0.2 % of the hits more than half a texel off). gl::MeshRelief works about the middle of
// the vertices' box (MeshRelief::origin), the eye and the projection moved there in double,
// so where the mesh lies and where the eye is do not count: the grids at x, z = 1e4 and 1e5
// at s = 1e-8, 0.01 and 0.1 matched the reference, and at 1e6 their normals did (the AOV's
// float positions cannot show hits to a texel there).
//  1. The shell no more than kMaxShellPerSize times the mesh's box diagonal: shells 6 and
//     60 times the grid's size, framed by the default camera, matched the reference (0 of
//     about 45 hits off), 605 times had 2 of 45 hits off, 6050 times 17 of 44, and at
//     --height-scale 1e9 (6e8 times) every hit was off.
//  2. The shell at least kMinShellPerSize times the diagonal (2^-64): the shader's
//     s-scaled terms keep their relative precision down to float's smallest numbers; the
//     grids matched the reference with shells 6e-31 of the diagonal (s = 1e-30) and lost
//     every normal at 6e-37 (s = 1e-36, float's underflow).
//  3. The vertices within kMaxWorldPosition of the origin, as every position of a scene
//     (core/scene/FloatLimits.h): the default camera frames the mesh from beyond it.
constexpr double kMaxShellPerSize = 16.0;
const double kMinShellPerSize = std::ldexp(1.0, -64);

void checkMeshFloatLimits(const TriangleMesh& mesh, const HeightMap& map, double heightScale,
                          const std::string& source) {
    checkMeshFloatLimits(mesh, map.maxValue(), heightScale, source);
}

void checkMeshFloatLimits(const TriangleMesh& mesh, double top, double heightScale,
                          const std::string& source) {
    const MeshSize size = meshSize(mesh);
    const double shell = heightScale * top;  // s H, the mesh's units
    const std::string shellText = "the shell ({heightScale} " + figure(heightScale) +
                                  " x the map's largest height " + figure(top) + " = " +
                                  figure(shell) + " mesh units)";
    if (!(shell <= kMaxShellPerSize * size.diagonal)) {
        throwBadInput(source + ": " + shellText + " is more than " + figure(kMaxShellPerSize) +
                      " times the mesh's size (its box's diagonal, " + figure(size.diagonal) +
                      "), past what the shader's float solve traces exactly; lower "
                      "{heightScale} (it is in the mesh's units)");
    }
    if (shell > 0.0 && !(shell >= kMinShellPerSize * size.diagonal)) {
        throwBadInput(source + ": " + shellText + " is less than 2^-64 of the mesh's size (its "
                      "box's diagonal, " + figure(size.diagonal) +
                      "), past float's range in the shader's solve; raise {heightScale} (it is "
                      "in the mesh's units)");
    }
    if (!(size.reach <= kMaxWorldPosition)) {
        throwBadInput(source + ": the mesh reaches " + figure(size.reach) +
                      " units from the origin, beyond the " + figure(kMaxWorldPosition) +
                      " a world position may lie from it; move the mesh nearer the origin");
    }
}

ReliefExtent meshShellExtent(const TriangleMesh& mesh, double heightScale, double top) {
    ReliefExtent extent;
    if (mesh.positions.empty()) return extent;
    glm::dvec3 low(mesh.positions.front()), high(low);
    for (const glm::vec3& p : mesh.positions) {
        low = glm::min(low, glm::dvec3(p));
        high = glm::max(high, glm::dvec3(p));
    }
    extent.topHeight = heightScale * top;  // s H, the mesh's units
    extent.min = low - glm::dvec3(extent.topHeight);
    extent.max = high + glm::dvec3(extent.topHeight);
    return extent;
}

Camera meshCamera(Camera camera, bool eyeGiven, bool targetGiven, const ReliefExtent& shell,
                  int width, int height) {
    const glm::dvec3 centre = 0.5 * (shell.min + shell.max);
    const double radius = 0.5 * glm::length(shell.max - shell.min);
    if (!targetGiven) camera.target = centre;
    if (!eyeGiven) {
        const Camera standard;
        const glm::dvec3 direction = glm::normalize(standard.eye - standard.target);
        // The half angle of the narrower field: vertical fovy / 2, horizontal from the aspect.
        const double tanY = std::tan(glm::radians(camera.fovyDegrees) * 0.5);
        const double tanX = tanY * (static_cast<double>(std::max(width, 1)) / std::max(height, 1));
        const double half = std::atan(std::min(tanX, tanY));
        // A sphere of radius r seen from distance d fills the half angle asin(r / d); from a
        // target off the centre, the distance to it more.
        const double distance =
            std::max(radius, 1e-300) / std::sin(half) + glm::length(camera.target - centre);
        camera.eye = camera.target + distance * direction;
    }
    return camera;
}

}  // namespace microrelief
