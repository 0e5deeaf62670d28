// A scene as plain values: what a relief is (ReliefDesc: its heights, how they lie over
// which base, its colours, its animation) and how it is looked at (ViewDesc: the camera,
// the picture, the method, the light). The renderers, the CPU twin and the programs are
// built from these and apply them (gl/ReliefRenderer.h, gl/HeadlessRender.h);
// nothing here knows a command line. docs/scene-and-cli.md is the convention every field
// follows.
//
// validate() reports every value that is wrong, by field: the path of the member as
// written here ("camera.eye", "base.radius", "heightScale"), and a sentence that names
// fields as {field} (core/Error.h), so a program can put its own names there (its flags)
// and a library user reads the fields'.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/core/base/TriangleMesh.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Camera.h"
#include "microrelief/core/scene/FloatLimits.h"
#include "microrelief/core/scene/Method.h"
#include "microrelief/core/scene/ModelTransform.h"
#include "microrelief/core/scene/SceneFields.h"

namespace microrelief {

struct FieldError {
    std::string field;    // "camera.eye"
    std::string message;  // "{camera.eye} and {camera.target} must differ"
    bool operator==(const FieldError&) const = default;
};

// Where a relief's heights come from: samples in memory, or an image file (read by the io
// component, io/HeightMapFile.h), or, with neither, the bundled default map.
struct MapSource {
    std::shared_ptr<const HeightMap> samples;   // first, where given
    std::optional<std::filesystem::path> file;  // else this file; else the bundled map
    HeightMapLoadOptions load;                  // the file's channel, normalisation

    bool bundled() const { return !samples && !file; }
    bool operator==(const MapSource& o) const {
        return samples == o.samples && file == o.file && load.channel == o.load.channel &&
               load.normalize == o.load.normalize && load.maxSide == o.load.maxSide;
    }
};

// The surface's colours: the bundled map's own with the bundled map (and none with any
// other map, or under an animated field that replaces its stones), none, or an image file
// over the map's (u, v).
struct AlbedoSource {
    enum class Kind { Default, None, File };
    Kind kind = Kind::Default;
    std::filesystem::path file;  // Kind::File
    bool operator==(const AlbedoSource&) const = default;
};

// The mesh base's triangles (docs/bases.md, "The mesh"): a mesh in memory, or an OBJ or glTF
// 2.0 file (read by the io component, io/MeshFile.h: loadMeshFile).
struct MeshSource {
    std::shared_ptr<const TriangleMesh> triangles;  // first, where given
    std::optional<std::filesystem::path> file;      // else this file

    bool given() const { return triangles || file; }
    bool operator==(const MeshSource&) const = default;
};

struct ReliefDesc {
    MapSource map;
    AlbedoSource albedo;
    BaseShape base;  // the surface the map is laid over, unless onMesh
    // The mesh base (microrelief-render's --base mesh --mesh FILE): the map laid over the
    // triangles of `mesh` (each prism X(b, t) = B(b) + s t D(b), s = heightScale in the
    // mesh's units) rather than over `base`, which then keeps the plane's defaults. Not a row
    // of the table of analytic bases (core/base/BaseType.h). validate() refuses here what the
    // mesh base does not draw yet: tiles, an animation, a model transform, an albedo file.
    bool onMesh = false;
    MeshSource mesh;  // given exactly when onMesh
    Interpolation interpolation = Interpolation::Bilinear;  // the last level
    glm::ivec2 tiles{1, 1};  // the map repeated N x M times across the base
    float heightScale = 0.1f;  // object height of map value 1 (plane); radius fraction (curved)
    ModelTransform model;      // where the relief sits in the world
    // An animated field over the map's grid (gl/AnimatedHeights.h), evaluated at
    // `time` seconds; empty: the map's own heights.
    std::string animation;
    double time = 0.0;

    bool operator==(const ReliefDesc& o) const;
    // Every value wrong on its own or with another of the relief's.
    std::vector<FieldError> validate() const;
};

struct ViewDesc {
    Camera camera;
    int width = 1280, height = 720;  // the picture, pixels
    MethodSettings method;           // how rays are traced (method.pixelError: the level of detail)
    ShadingOptions shading;          // light, shadows, debug view, colour without a texture
    glm::vec3 background{0.11f, 0.12f, 0.14f};  // linear RGB

    bool operator==(const ViewDesc& o) const;
    std::vector<FieldError> validate() const;
};

// What the two must agree on: the method runs on the relief's base and tiles, shadows
// take an exact method; on the mesh base, the view the mesh base draws so far (multilevel,
// exact, no shadows, the directional light, the shaded or the normal view).
std::vector<FieldError> validateTogether(const ReliefDesc& relief, const ViewDesc& view);
// Whether two reliefs have one max pyramid: the same heights (the map source and how it is
// loaded, the animation not counted: an animated field is written over the map's pyramid),
// the same addressing (u wraps on every curved base, not on the plane) and tiles. The rest
// of a relief (the base's kind among the curved ones and its sizes, the last level, whose
// surfaces the one pyramid bounds both, the height scale, the model, the albedo) a renderer
// applies without building the pyramid again.
bool samePyramid(const ReliefDesc& a, const ReliefDesc& b);

// Both, then together.
std::vector<FieldError> validateScene(const ReliefDesc& relief, const ViewDesc& view);

// The checks of a point and of a direction the shader gets as floats, on a value still in
// double (a command line's text, before a desc stores it in float: a light of 1e-300 is
// refused as too short, not rounded to zero first). validate() runs them on the desc. A
// point's components lie within `limit`: kMaxWorldPosition for a position (the renderer
// subtracts the eye in double first), kMaxWorldCoordinate for --up (core/scene/FloatLimits.h).
void checkPoint(std::vector<FieldError>& errors, const std::string& field, const glm::dvec3& p,
                double limit = kMaxWorldPosition);
void checkDirection(std::vector<FieldError>& errors, const std::string& field, const glm::dvec3& v);

// Throws Error(BadInput) with the first of `errors`; nothing when there are none.
void throwIfInvalid(const std::vector<FieldError>& errors);

// The largest picture, refused up front beyond: sides up to 65536 and at most 16384 x
// 16384 pixels, which a rendered frame holds in memory at kFrameBytesPerPixel (colour, the
// position AOV, the statistics and the shadow: 10 GiB at the limit). Larger than the GL's
// own limits, the headless renderer draws it in tiles (gl/HeadlessRender.h).
inline constexpr int kMaxPictureSide = 65536;
inline constexpr long long kMaxPicturePixels = 16384LL * 16384;
inline constexpr int kFrameBytesPerPixel = 4 + 16 + 16 + 4;
// What ViewDesc::validate says of a picture size beyond the limits above; nothing within.
std::optional<FieldError> pictureSizeError(int width, int height);
// Throws Error(BadInput) with pictureSizeError's message.
void checkPictureSize(int width, int height);
// The most tiles a side (the whole map's side in float map coordinates stays exact to 2^-7
// of a texel at 256 tiles of a 256 map).
inline constexpr int kMaxTiles = 4096;
// The largest |time| an animated relief is drawn at, in seconds (about 32 years): its
// phases are reduced on the host in double, whose time is then exact to 1.2e-7 s.
inline constexpr double kMaxAnimationSeconds = 1e9;

// The animated fields (gl/AnimatedHeights.h draws them): waves, ripples, flood.
const std::vector<std::string>& animatedFieldNames();
// Whether the field shows the map's own heights (flood) rather than replacing them (waves,
// ripples): the map's colours then still belong on it.
inline bool animatedFieldShowsTheMap(const std::string& name) { return name == "flood"; }

}  // namespace microrelief
