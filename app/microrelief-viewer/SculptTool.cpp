#include "SculptTool.h"

#include <algorithm>

namespace microrelief {

SculptTool::SculptTool(const GL& gl, const std::filesystem::path& shaderDir)
    : editor_(gl, shaderDir), footprint_(gl, shaderDir) {}

std::vector<TexelRect> SculptTool::dab(ReliefRenderer& renderer, const HeightMap& map,
                                       const ReliefDesc& relief, const glm::dvec2& mapPoint,
                                       const Brush& brush, bool invert) {
    if (!history_.strokeActive()) {
        history_.startStroke();
        flattenLevel_ = static_cast<float>(
            map.surface(mapPoint.x, mapPoint.y, relief.base.wrapsU(), relief.interpolation));
    }
    const std::vector<TexelRect> changed =
        editor_.dab(renderer, mapPoint, strokeBrush(brush, flattenLevel_, invert));
    // A stroke is one of the map's states once it changes a sample (the editor drops one
    // that changes none).
    if (!changed.empty()) history_.strokeChanged();
    return changed;
}

bool SculptTool::endStroke() {
    editor_.endStroke();
    return history_.endStroke();
}

std::vector<TexelRect> SculptTool::undo(ReliefRenderer& renderer) {
    std::vector<TexelRect> changed = editor_.undo(renderer);
    if (!changed.empty()) history_.undone();
    return changed;
}

void SculptTool::clear() {
    editor_.clear();
    history_.clear();
}

void SculptTool::drawFootprint(const HeightMap& map, const ReliefDesc& relief,
                               const glm::dvec2& centre, const Brush& brush,
                               const CameraFrame& camera) {
    const std::vector<glm::vec3> ring = footprintRing(map, relief.base, relief.interpolation,
                                                      relief.heightScale, relief.model, centre,
                                                      brush.radius);
    const bool lowering = brush.mode == BrushMode::Lower;
    footprint_.draw(
        ring, glm::mat4(camera.viewProjection), glm::vec3(camera.eye),
        lowering ? glm::vec4(0.3f, 0.6f, 1.0f, 1.0f) : glm::vec4(1.0f, 0.75f, 0.2f, 1.0f));
}

void copyChangedSamples(const GL& gl, const ReliefTextures& textures,
                        const std::vector<TexelRect>& changed, HeightMap& map) {
    for (const TexelRect& rect : changed) {
        const std::vector<float> values = textures.readSamples(gl, rect);
        for (int j = rect.y0; j < rect.y1; ++j)
            std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(j - rect.y0) * rect.width(),
                        rect.width(), &map.at(rect.x0, j));
    }
}

}  // namespace microrelief
