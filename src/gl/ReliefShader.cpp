#include "microrelief/gl/ReliefShader.h"

#include <vector>

#include "microrelief/core/Error.h"
#include "microrelief/core/GlslConstants.h"
#include "microrelief/gl/PagedPyramid.h"
#include "microrelief/gl/ShaderProgram.h"

namespace microrelief {

namespace {

// The numbers cast into the #defines below (and into the block's debugView) are the C++
// enums' values; the GLSL names them in shaders/microrelief/variants.glsl and
// debug_views.glsl, whose values core/GlslConstants.h carries (generated from the GLSL,
// cmake/Contracts.cmake). Each member is held to its GLSL name, and each enum's count to
// the GLSL's, so a member reordered, added or renamed on one side stops the build here.
template <typename Enum>
constexpr bool is(Enum member, int glsl) {
    return static_cast<int>(member) == glsl;
}

static_assert(is(Method::Multilevel, glsl::kMethodMultilevel) &&
                  is(Method::Normal, glsl::kMethodNormal) &&
                  is(Method::Offset, glsl::kMethodOffset) &&
                  is(Method::Steep, glsl::kMethodSteep) && is(Method::Pom, glsl::kMethodPom) &&
                  is(Method::Relief, glsl::kMethodRelief) &&
                  is(Method::MaxMip, glsl::kMethodMaxmip) && is(Method::Cone, glsl::kMethodCone) &&
                  is(Method::Rcsm, glsl::kMethodRcsm) && is(Method::Rcsm, glsl::kMethodCount - 1),
              "Method and the MR_METHOD_* of variants.glsl differ");
// BaseKind is not held here: its enumerators are generated from MR_BASE_* (BaseShape.h).
static_assert(is(Interpolation::Bilinear, glsl::kInterpolationBilinear) &&
                  is(Interpolation::Biquadratic, glsl::kInterpolationBiquadratic) &&
                  is(Interpolation::Biquadratic, glsl::kInterpolationCount - 1),
              "Interpolation and the MR_INTERPOLATION_* of variants.glsl differ");
static_assert(is(ShadowMode::Off, glsl::kShadowModeOff) &&
                  is(ShadowMode::Hard, glsl::kShadowModeHard) &&
                  is(ShadowMode::Soft, glsl::kShadowModeSoft) &&
                  is(ShadowMode::Soft, glsl::kShadowModeCount - 1),
              "ShadowMode and the MR_SHADOWS_* of variants.glsl differ");
static_assert(is(DepthLayout::Any, glsl::kDepthLayoutAny) &&
                  is(DepthLayout::Greater, glsl::kDepthLayoutGreater) &&
                  is(DepthLayout::Less, glsl::kDepthLayoutLess) &&
                  is(DepthLayout::Less, glsl::kDepthLayoutCount - 1),
              "DepthLayout and the MR_DEPTH_LAYOUT_* of variants.glsl differ");
static_assert(is(DebugView::Shaded, glsl::kDebugViewShaded) &&
                  is(DebugView::Iterations, glsl::kDebugViewIterations) &&
                  is(DebugView::Level, glsl::kDebugViewLevel) &&
                  is(DebugView::Normal, glsl::kDebugViewNormal) &&
                  is(DebugView::Depth, glsl::kDebugViewDepth) &&
                  is(DebugView::Position, glsl::kDebugViewPosition) &&
                  is(DebugView::Position, glsl::kDebugViewCount - 1),
              "DebugView and the MR_DEBUG_VIEW_* of debug_views.glsl differ");

}  // namespace

std::string describe(const ReliefShaderConfig& config) {
    return std::string("relief (") + methodName(config.method) + ", " +
           baseName(BaseShape{config.base}) + ", " + interpolationName(config.interpolation) +
           (config.paged ? ", paged" : "") + (config.glsl330 ? ", GLSL 3.30" : "") +
           (config.coarseTile > 0 ? ", coarse " + std::to_string(config.coarseTile) : "") + ")";
}

ReliefShader::ReliefShader(const GL& gl, const std::filesystem::path& shaderDir,
                           const ReliefShaderConfig& config)
    : gl_(&gl), config_(config) {
    GLint major = 0;
    gl.GetIntegerv(GL_MAJOR_VERSION, &major);
    const std::string version = config.paged                    ? "430 core"
                                : major >= 4 && !config.glsl330 ? "400 core"
                                                                : "330 core";
    std::vector<ShaderDefine> defines = {
        {"MICRORELIEF_METHOD", std::to_string(static_cast<int>(config.method))},
        {"MICRORELIEF_BASE", std::to_string(static_cast<int>(config.base))},
        {"MICRORELIEF_INTERPOLATION", std::to_string(static_cast<int>(config.interpolation))},
        {"MICRORELIEF_DEPTH_LAYOUT", std::to_string(static_cast<int>(config.depthLayout))},
        {"MICRORELIEF_SHADOWS", std::to_string(static_cast<int>(config.shadows))},
        {"MICRORELIEF_ALBEDO_MAP", config.albedoMap ? "1" : "0"},
        {"MICRORELIEF_TILING", config.tiled ? "1" : "0"}};
    if (config.countFetches) defines.push_back({"MICRORELIEF_COUNT_FETCHES", ""});
    if (config.coarseTile > 0)
        defines.push_back({"MICRORELIEF_COARSE_TILE", std::to_string(config.coarseTile)});
    if (config.paged) {
        defines.push_back({"MICRORELIEF_PAGED", "1"});
        defines.push_back({"MICRORELIEF_PAGE_INFO_AT", std::to_string(PageTableLayout::kInfoAt)});
        defines.push_back(
            {"MICRORELIEF_PAGE_LEVELS_AT", std::to_string(PageTableLayout::kLevelsAt)});
        defines.push_back(
            {"MICRORELIEF_PAGE_ENTRIES_AT", std::to_string(PageTableLayout::kEntriesAt)});
    }
    const gl::Shader vertex = gl::compileShader(
        gl, GL_VERTEX_SHADER, assembleShader(shaderDir / "relief_box.vert", version));
    const gl::Shader fragment = gl::compileShader(
        gl, GL_FRAGMENT_SHADER, assembleShader(shaderDir / "relief.frag", version, defines));
    program_ = gl::linkProgram(gl, vertex, fragment, describe(config));

    // The units and the block binding, once: glUniform* needs the program current.
    GLint previous = 0;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &previous);
    gl.UseProgram(program_.id());
    gl.Uniform1i(gl::uniform(gl, program_, "maxPyramid"), kMaxPyramidUnit);
    gl.Uniform1i(gl::uniform(gl, program_, "heightSamples"), kHeightsUnit);
    gl.Uniform1i(gl::uniform(gl, program_, "windowPyramid"), kWindowPyramidUnit);
    gl.Uniform1i(gl::uniform(gl, program_, "albedoMap"), kAlbedoUnit);
    gl.Uniform1i(gl::uniform(gl, program_, "coneMap"), kConeMapUnit);
    if (config.coarseTile > 0)
        gl.Uniform1i(gl::uniform(gl, program_, "coarseStart"), kCoarseStartUnit);
    if (config.paged) {
        gl.Uniform1i(gl::uniform(gl, program_, "mr_pagePool"), kPagePoolUnit);
        gl.Uniform1i(gl::uniform(gl, program_, "mr_pageCoarse"), kWindowPyramidUnit);
    }
    gl.UseProgram(static_cast<GLuint>(previous));
    const GLuint block = gl.GetUniformBlockIndex(program_.id(), "MicroreliefParameters");
    if (block == GL_INVALID_INDEX)
        throwRuntime(describe(config) + ": the program has no MicroreliefParameters block");
    gl.UniformBlockBinding(program_.id(), block, kParametersBinding);
}

ReliefShader& ReliefShader::bindTexture(GLuint unit, GLuint texture) {
    gl_->ActiveTexture(GL_TEXTURE0 + unit);
    gl_->BindTexture(GL_TEXTURE_2D, texture);
    return *this;
}

ReliefShader& ReliefShader::bindMaxPyramid(GLuint texture) {
    return bindTexture(kMaxPyramidUnit, texture);
}

ReliefShader& ReliefShader::bindHeights(GLuint texture) {
    return bindTexture(kHeightsUnit, texture);
}

ReliefShader& ReliefShader::bindWindowPyramid(GLuint texture) {
    return bindTexture(kWindowPyramidUnit, texture);
}

ReliefShader& ReliefShader::bindAlbedo(GLuint texture) {
    return bindTexture(kAlbedoUnit, texture);
}

ReliefShader& ReliefShader::bindConeMap(GLuint texture) {
    return bindTexture(kConeMapUnit, texture);
}

ReliefShader& ReliefShader::bindParameters(GLuint buffer) {
    gl_->BindBufferBase(GL_UNIFORM_BUFFER, kParametersBinding, buffer);
    return *this;
}

void ReliefShader::use() const {
    gl_->UseProgram(program_.id());
}

GLint ReliefShader::parameterOffset(const std::string& member) const {
    const GLchar* name = member.c_str();
    GLuint index = GL_INVALID_INDEX;
    gl_->GetUniformIndices(program_.id(), 1, &name, &index);
    if (index == GL_INVALID_INDEX) return -1;
    GLint offset = -1;
    gl_->GetActiveUniformsiv(program_.id(), 1, &index, GL_UNIFORM_OFFSET, &offset);
    return offset;
}

GLint ReliefShader::parametersSize() const {
    const GLuint block = gl_->GetUniformBlockIndex(program_.id(), "MicroreliefParameters");
    GLint size = 0;
    gl_->GetActiveUniformBlockiv(program_.id(), block, GL_UNIFORM_BLOCK_DATA_SIZE, &size);
    return size;
}

}  // namespace microrelief
