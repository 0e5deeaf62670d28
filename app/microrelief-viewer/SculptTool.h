// The sculpting tool on the GPU: dabs and strokes on the renderer's map (gl/HeightEditor.h),
// their undo, the history of the map's edit states (StrokeHistory.h), and the brush's
// footprint drawn under the cursor (BrushFootprint.h). The viewer says where and when to
// paint; what a dab or an undo changed comes back as texel rectangles, which the viewer
// reads into its CPU mirror of the map (copyChangedSamples).
#pragma once

#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "BrushFootprint.h"
#include "StrokeHistory.h"
#include "microrelief/core/heightmap/HeightMap.h"
#include "microrelief/core/scene/Scene.h"
#include "microrelief/gl/HeightEditor.h"
#include "microrelief/gl/ReliefRenderer.h"

namespace microrelief {

class SculptTool {
public:
    // Compiles the brush and the footprint from `shaderDir`. Throws Error(Runtime).
    SculptTool(const GL& gl, const std::filesystem::path& shaderDir);

    // One dab of `brush` at `mapPoint` (texels) on `renderer`'s map; the stroke's first dab
    // takes the height of `map` (the CPU mirror) under it as flatten's level, and `invert`
    // swaps raise and lower. Returns the samples it changed. Throws as HeightEditor::dab.
    std::vector<TexelRect> dab(ReliefRenderer& renderer, const HeightMap& map,
                               const ReliefDesc& relief, const glm::dvec2& mapPoint,
                               const Brush& brush, bool invert);
    bool strokeActive() const { return history_.strokeActive(); }
    // The dabs since the stroke began are one step of undo; whether they changed the map.
    bool endStroke();
    // The last stroke undone; the samples written back (none: nothing to undo).
    std::vector<TexelRect> undo(ReliefRenderer& renderer);
    int undoSteps() const { return editor_.undoSteps(); }
    // Whether the map differs from the state last saved or opened.
    bool edited() const { return history_.edited(); }
    // The map as it is now was saved.
    void saved() { history_.saved(); }
    // Another map: its history forgotten.
    void clear();

    // The ring of `brush` round `centre` (texels) on `map`'s surface, drawn into the bound
    // framebuffer as `camera` sees it (blue while lowering, amber otherwise).
    void drawFootprint(const HeightMap& map, const ReliefDesc& relief, const glm::dvec2& centre,
                       const Brush& brush, const CameraFrame& camera);

private:
    HeightEditor editor_;
    BrushFootprint footprint_;
    StrokeHistory history_;
    float flattenLevel_ = 0.0f;  // the height under the stroke's first dab
};

// The samples `changed` on the GPU (`textures`) copied into `map`, the CPU mirror of them.
void copyChangedSamples(const GL& gl, const ReliefTextures& textures,
                        const std::vector<TexelRect>& changed, HeightMap& map);

}  // namespace microrelief
