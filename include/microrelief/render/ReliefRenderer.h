// Draws microrelief with the multilevel method: the base surface's bounding box is the
// proxy geometry, and each of its fragments traces its own ray (shaders/relief.frag).
// Owns the GL objects it needs; draws into whatever framebuffer is bound, which must
// have the three colour outputs of relief.frag (see OffscreenTarget).
#pragma once

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

#include <glm/glm.hpp>

#include "microrelief/base/BaseShape.h"
#include "microrelief/base/ReliefExtent.h"
#include "microrelief/gl/Objects.h"
#include "microrelief/heightmap/HeightMap.h"
#include "microrelief/heightmap/MaxPyramid.h"
#include "microrelief/render/Camera.h"

namespace microrelief {

// How each pixel's ray is traced (relief.frag's MICRORELIEF_METHOD): the paper's
// multilevel method, or one of the peers it is measured against.
enum class Method { Multilevel = 0, Normal, Offset, Steep, Pom, Relief, MaxMip };

// "multilevel", "normal", "offset", "steep", "pom", "relief", "maxmip"; throws Error(BadInput).
Method parseMethod(const std::string& name);
const char* methodName(Method method);
// Whether a method's quality knob is a step count (steep, pom, relief).
bool methodHasSteps(Method method);
// Whether a method traces the whole solid, side walls and bottom face included
// (multilevel, maxmip); the others know the top surface only.
bool methodTracesTheSolid(Method method);
// Whether a method runs on a base: every method on the plane; on a curved base the exact
// ones (multilevel, maxmip) and the peers engines ship there, pom and relief stepping in
// the base's tangent frame. Otherwise throws Error(BadInput) naming both flags.
void checkMethodSupportsBase(Method method, const BaseShape& base);
bool methodRunsOnBase(Method method, const BaseShape& base);

struct MethodSettings {
    Method method = Method::Multilevel;
    int steps = 64;           // steep: layers; pom: samples at grazing angles; relief: linear steps
    int minSteps = 16;        // pom: samples looking straight down (setSteps: a quarter, >= 4)
    int refineSteps = 8;      // relief: binary search steps
    float pixelError = 0.0f;  // multilevel: tolerated error in pixels; 0 is exact

    // The step budget and what follows from it, the one rule every program uses.
    void setSteps(int n) {
        steps = n;
        minSteps = std::min(n, std::max(4, n / 4));
    }
};

// What relief.frag writes to the picture (debug_views.glsl).
enum class DebugView { Shaded = 0, Iterations, Level, Normal, Depth, Position };

// "shaded", "iterations", "level", "normal", "depth", "position"; throws Error(BadInput).
DebugView parseDebugView(const std::string& name);
const char* debugViewName(DebugView view);

struct ShadingOptions {
    glm::vec3 lightDirection =
        glm::normalize(glm::vec3(-0.45f, 0.8f, -0.35f));  // towards the light
    glm::vec3 albedo{0.60f, 0.58f, 0.55f};
    DebugView view = DebugView::Shaded;
};

// The part of the picture one draw covers, in GL window coordinates of the whole
// picture (origin at the bottom left): the bound framebuffer holds width x height
// pixels of it from (x, y). The default, width 0, is the whole picture.
struct PictureTile {
    int x = 0, y = 0;
    int width = 0, height = 0;
};

class ReliefRenderer {
public:
    // `shaderDir` holds relief_box.vert, relief.frag and microrelief/; `method` is the
    // program compiled first.
    ReliefRenderer(const GL& gl, const std::filesystem::path& shaderDir,
                   const MethodSettings& method = {});

    // Builds the max pyramid of `map` laid over `base` (wrapped in u on a curved base), of
    // the surface `interpolation` makes of it, and uploads it with the samples. Throws
    // Error(BadInput) when the map exceeds GL_MAX_TEXTURE_SIZE or the method does not run on that
    // base; `source` names the map in that message.
    void setHeightMap(const HeightMap& map, const std::string& source, const BaseShape& base = {},
                      Interpolation interpolation = Interpolation::Bilinear);
    void setHeightScale(float scale);
    // Another base of the same addressing as the map was uploaded with (the curved bases
    // among themselves, a new size of the same one); a change between the plane and a
    // curved base needs setHeightMap. Throws Error(BadInput) for a method that does not run
    // on it, keeping the base it had.
    void setBase(const BaseShape& base);
    const BaseShape& base() const { return base_; }
    Interpolation interpolation() const { return interpolation_; }

    // Recompiles the current program from the files; on failure throws and keeps the
    // previous program. Other programs compiled before are dropped (they may be stale).
    void reloadShaders();

    // Chooses the tracing method; each (method, instrumentation) pair is compiled once
    // and kept. Step counts and the pixel error are uniforms. `countFetches` selects the
    // instrumented variant that writes texel reads to the statistics output. On a
    // compile failure throws and keeps the method that works.
    void setMethod(const MethodSettings& settings, bool countFetches = false);
    const MethodSettings& method() const { return method_; }

    // Draws the picture `camera` describes, or the tile of it given: the same rays, so a
    // picture drawn in tiles is the one drawn whole, pixel for pixel.
    void draw(const CameraFrame& camera, const ShadingOptions& shading,
              const PictureTile& tile = {});

    int maxIterations() const { return maxIterations_; }

private:
    // A linked program and the uniform locations looked up in it so far.
    struct CompiledProgram {
        gl::Program program;
        std::unordered_map<std::string, GLint> uniforms;
    };
    // Method, counts fetches, base, interpolation.
    using ProgramKey = std::tuple<Method, bool, BaseKind, Interpolation>;

    CompiledProgram compile(const ProgramKey& key) const;
    // The program for the key, compiled on first use; throws and changes nothing on failure.
    CompiledProgram& program(const ProgramKey& key);
    GLint uniform(const char* name);
    void uploadBox();

    const GL& gl_;
    std::filesystem::path shaderDir_;
    std::map<ProgramKey, CompiledProgram> programs_;
    CompiledProgram* current_ = nullptr;
    gl::Texture pyramidTexture_;  // aligned max levels (maxmip)
    gl::Texture windowTexture_;   // overlapping max levels (multilevel)
    gl::Texture sampleTexture_;
    gl::VertexArray boxArray_;
    gl::Buffer boxVertices_;
    gl::Buffer boxIndices_;
    int mapWidth_ = 0, mapHeight_ = 0;  // 0: no map yet
    int pyramidWidth_ = 0, pyramidHeight_ = 0, pyramidLevels_ = 0;
    float maxHeight_ = 0.0f;
    float heightScale_ = 0.1f;
    int maxIterations_ = 0;
    MethodSettings method_;
    bool countFetches_ = false;
    BaseShape base_;
    bool wrapsU_ = false;  // the addressing the map's pyramid was built with
    Interpolation interpolation_ = Interpolation::Bilinear;  // the surface it bounds
};

}  // namespace microrelief
