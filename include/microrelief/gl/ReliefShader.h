// The relief program as a typed shader object (Magnum's Shaders::PhongGL): one
// configuration of relief_box.vert and relief.frag compiled and linked, its texture units
// and its uniform block fixed once in the constructor, the textures bound through named
// calls, and the block (MicroreliefParameters, shaders/relief_parameters.glsl) mirrored by
// ReliefParameters. ReliefRenderer draws with it; an engine that keeps its own geometry
// and buffers may draw with it too.
#pragma once

#include <compare>
#include <cstddef>
#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "microrelief/core/base/BaseShape.h"
#include "microrelief/gl/Objects.h"
#include "microrelief/gl/ReliefParameters.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Method.h"

namespace microrelief {

// What the depth a fragment writes promises against the depth of the proxy face it comes
// from (relief.frag's MICRORELIEF_DEPTH_LAYOUT): nothing, greater or equal (a front face,
// the hit behind it, with a standard depth test), or less or equal (a back face, the hit
// before it; or a front face under reversed-Z). With the promise the GL may keep its early
// depth test (conservative depth, GL 4.2 or ARB_conservative_depth).
enum class DepthLayout { Any = 0, Greater = 1, Less = 2 };

// The caller's depth convention, which gl_FragDepth follows: the clip-space range of z / w
// ([-1, 1], OpenGL's default, or [0, 1] after glClipControl(..., GL_ZERO_TO_ONE)) and
// whether near maps to the far end of the depth range (reversed-Z: a projection that
// does so, a depth test of GL_GREATER and a depth cleared to 0). The window depth is
// glDepthRange applied to the first, as the fixed-function path does; the projection
// itself is the caller's (CameraFrame::viewProjection).
struct DepthConvention {
    bool zeroToOne = false;
    bool reversed = false;

    bool operator==(const DepthConvention&) const = default;
};

// One variant of the program: relief.frag's macros.
struct ReliefShaderConfig {
    Method method = Method::Multilevel;
    BaseKind base = BaseKind::Plane;
    Interpolation interpolation = Interpolation::Bilinear;
    bool countFetches = false;  // the instrumented variant: texel reads in the statistics
    DepthLayout depthLayout = DepthLayout::Any;
    ShadowMode shadows = ShadowMode::Off;
    bool albedoMap = false;  // the surface's colour from an albedo texture (unit 3)
    bool tiled = false;      // the map repeated (MICRORELIEF_TILING)
    bool paged = false;      // the map read through pages (MICRORELIEF_PAGED; GLSL 4.30)
    // GLSL 3.30 in a newer context too: the path of an engine in a GL 3.3 context (four
    // texel reads a bilinear cell where 4.00 gathers them; ES 3.00 reads so too). Not for
    // paged maps, which need 4.30.
    bool glsl330 = false;
    // The multilevel method on the plane after the coarse pass (shaders/coarse_start.frag):
    // each pixel starts where its coarseTile x coarseTile tile may first meet the solid,
    // read from unit 6 (kCoarseStartUnit). 0: the single pass.
    int coarseTile = 0;

    auto operator<=>(const ReliefShaderConfig&) const = default;
};

// The uniform block MicroreliefParameters, std140, is ReliefParameters
// (microrelief/gl/ReliefParameters.h), generated at build time from
// shaders/relief_parameters.glsl, which says what each member is; a GL test holds every
// offset to the linked program's too.

class ReliefShader {
public:
    // The fixed bindings: the aligned max pyramid (maxmip), the samples, the overlapping
    // pyramid (multilevel) and the albedo on texture units 0 to 3, the parameters on
    // uniform buffer binding 0.
    static constexpr GLuint kMaxPyramidUnit = 0;
    static constexpr GLuint kHeightsUnit = 1;
    static constexpr GLuint kWindowPyramidUnit = 2;
    static constexpr GLuint kAlbedoUnit = 3;
    static constexpr GLuint kConeMapUnit = 4;  // cone and rcsm's cone map (peers/ConeMap.h)
    // A paged map's pool (a texture array, gl/PagedPyramid.h) and its page table and wants
    // (shader storage bindings); its coarse windows are the window pyramid's unit.
    static constexpr GLuint kPagePoolUnit = 5;
    static constexpr GLuint kCoarseStartUnit = 6;  // the coarse pass's starts (coarseTile > 0)
    static constexpr GLuint kPageTableBinding = 1;
    static constexpr GLuint kPageWantsBinding = 2;
    static constexpr GLuint kParametersBinding = 0;

    // Compiles `config` of relief_box.vert and relief.frag from `shaderDir` (the folder
    // holding them and microrelief/), as GLSL 4.00 core where the GL has it (a patch's
    // samples in one textureGather), else 3.30 core; a paged one as GLSL 4.30. Throws
    // Error(Runtime) with the compiler's log mapped to the files on failure. Leaves the current
    // program as it was.
    ReliefShader(const GL& gl, const std::filesystem::path& shaderDir,
                 const ReliefShaderConfig& config);

    // Bind textures to this program's units (glActiveTexture + glBindTexture), and the
    // parameters' buffer to its binding; they change GL state the caller may restore.
    ReliefShader& bindMaxPyramid(GLuint texture);
    ReliefShader& bindHeights(GLuint texture);
    ReliefShader& bindWindowPyramid(GLuint texture);
    ReliefShader& bindAlbedo(GLuint texture);
    ReliefShader& bindConeMap(GLuint texture);
    ReliefShader& bindParameters(GLuint buffer);
    void use() const;

    const ReliefShaderConfig& config() const { return config_; }
    GLuint id() const { return program_.id(); }
    // The byte offset of a member of MicroreliefParameters in the linked program, -1 if
    // the compiler dropped it (unused): what the tests compare ReliefParameters with.
    GLint parameterOffset(const std::string& member) const;
    // The block's size in the linked program.
    GLint parametersSize() const;

private:
    ReliefShader& bindTexture(GLuint unit, GLuint texture);

    const GL* gl_;
    ReliefShaderConfig config_;
    gl::Program program_;
};

// "relief (multilevel, plane, bilinear)": a configuration in messages.
std::string describe(const ReliefShaderConfig& config);

}  // namespace microrelief
