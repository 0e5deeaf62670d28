// An animated relief (issue 16): a height field that changes with time, evaluated on the
// GPU into the renderer's samples (shaders/edit/animate.frag), its max pyramids built anew
// on the GPU every time (ReliefRenderer::heightsReplaced). The field has the map's size;
// `flood` also reads the map's own heights.
//
//   waves    four travelling sine waves, seamless round a curved base
//   ripples  rings running out from the middle
//   flood    the map under water that rises and falls, with waves on it
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/gl/Objects.h"
#include "microrelief/core/scene/Scene.h"

namespace microrelief {

class ReliefRenderer;


class AnimatedHeights {
public:
    // The fields (core/scene/Scene.h: animatedFieldNames, animatedFieldShowsTheMap).
    // Throws Error(BadInput), naming the field and the names, for an unknown one.
    static void checkName(const std::string& name);

    // Compiles the field's pass from `shaderDir`. Throws Error.
    AnimatedHeights(const GL& gl, const std::filesystem::path& shaderDir, const std::string& name);

    const std::string& name() const { return name_; }
    // The field at `seconds` into `renderer`'s samples, then its pyramids and box. The first
    // call after construction or forgetMap() keeps a copy of the map's samples, the ground
    // `flood` floods (the samples then hold the field, not the map).
    void evaluate(ReliefRenderer& renderer, double seconds);
    // Another map was set: its samples are the ground from the next evaluate on.
    void forgetMap() { baseSize_ = glm::ivec2(0); }
    // Whether the renderer's samples hold the field (evaluated since the last forgetMap).
    bool evaluated() const { return baseSize_ != glm::ivec2(0); }
    // The map's own samples back into `renderer`, its pyramids built anew; then forgetMap.
    void restore(ReliefRenderer& renderer);

private:
    const GL& gl_;
    std::string name_;
    int field_ = 0;
    gl::Program program_;
    GLint mapSize_ = -1, wavePhase_ = -1, floodWavePhase_ = -1, ripplePhase_ = -1, floodPhase_ = -1;
    GLint fieldLocation_ = -1;
    gl::VertexArray vertexArray_;
    gl::Framebuffer framebuffer_;
    gl::Texture base_;
    glm::ivec2 baseSize_{0};
};

}  // namespace microrelief
