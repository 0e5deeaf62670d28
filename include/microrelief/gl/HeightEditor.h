// Sculpting a map on the GPU: brush dabs drawn into the renderer's samples texture
// (shaders/edit/brush.frag), the max pyramids brought up to date over what each dab
// changed (ReliefRenderer::heightsChanged, gl/PyramidBuilder.h), and undo by strokes.
//
// A dab copies the samples round it into a scratch texture, then draws the new heights
// over the samples it reaches, each read from the copy: no pass reads what it writes.
// Before it draws, it reads the samples it will change back to the host; undo writes them
// back, exactly, last dab first. The history keeps at most kUndoBudgetBytes of them, the
// oldest strokes going first.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "microrelief/gl/Objects.h"
#include "microrelief/core/heightmap/MaxPyramid.h"

namespace microrelief {

class ReliefRenderer;

enum class BrushMode { Raise = 0, Lower = 1, Smooth = 2, Flatten = 3 };
// "raise", "lower", "smooth", "flatten".
const char* brushModeName(BrushMode mode);

struct Brush {
    BrushMode mode = BrushMode::Raise;
    double radius = 8.0;     // map texels; the falloff is (1 - d^2)^2 of the distance in radii
    float strength = 0.02f;  // raise, lower: map units at the centre per dab; smooth,
                             // flatten: the fraction of the way per dab (at most 1)
    float level = 0.5f;      // flatten: the height it moves towards, map units
    float ceiling = 1e6f;    // the largest height a dab leaves, map units
};

class HeightEditor {
public:
    static constexpr std::size_t kUndoBudgetBytes = std::size_t(256) << 20;

    // Compiles the brush from `shaderDir` (edit/ and microrelief/). Throws Error(Runtime).
    HeightEditor(const GL& gl, const std::filesystem::path& shaderDir);

    // One dab centred at map point `centre` (texels: X = u W, Y = v H) on `renderer`'s
    // map, whose pyramids it updates; returns the samples it changed (none outside the
    // map; on a curved base a dab over the seam changes columns on both sides). Throws
    // Error(BadInput) for a radius or strength that is not a positive finite number.
    std::vector<TexelRect> dab(ReliefRenderer& renderer, const glm::dvec2& centre,
                               const Brush& brush);
    // The dabs since the last endStroke are one step of undo.
    void endStroke();
    // The samples before the last stroke, back exactly as they were, and the pyramids over
    // them; returns the samples it wrote back, none when there was nothing to undo.
    std::vector<TexelRect> undo(ReliefRenderer& renderer);
    int undoSteps() const;
    // Forgets the history (another map).
    void clear();

private:
    struct Change {
        TexelRect rect;
        std::vector<float> before;  // rect's samples before the dab, row 0 first
    };
    // The samples of `source` (unwrapped columns: wrapped round on a curved base) into
    // the scratch texture, at its origin.
    void copyToScratch(GLuint samples, int mapWidth, bool wrapU, const TexelRect& source);
    void trimHistory();

    const GL& gl_;
    gl::Program program_;
    GLint sourceOrigin_ = -1, mapSize_ = -1, wrapU_ = -1, shift_ = -1, centre_ = -1, radius_ = -1,
          strength_ = -1, mode_ = -1, level_ = -1, ceiling_ = -1;
    gl::VertexArray vertexArray_;
    gl::Framebuffer read_, draw_;
    gl::Texture scratch_;
    glm::ivec2 scratchSize_{0};
    std::vector<std::vector<Change>> strokes_;
    bool strokeOpen_ = false;
};

}  // namespace microrelief
