#include "microrelief/gl/ReliefPrograms.h"

#include <utility>

namespace microrelief {

ReliefPrograms::ReliefPrograms(const GL& gl, std::filesystem::path shaderDir)
    : gl_(gl), shaderDir_(std::move(shaderDir)) {}

ReliefShader& ReliefPrograms::program(const ReliefShaderConfig& config, bool* compiled) {
    auto found = programs_.find(config);
    const bool compiles = found == programs_.end();
    if (compiles) {
        // Compiled before it is inserted: a failure leaves the map as it was.
        found = programs_.emplace(config, ReliefShader(gl_, shaderDir_, config)).first;
        ++compiled_;
    }
    if (compiled) *compiled = compiles;
    return found->second;
}

void ReliefPrograms::reload(const ReliefShaderConfig& config) {
    ReliefShader fresh(gl_, shaderDir_, config);  // throws before anything changes
    ++compiled_;
    programs_.clear();
    programs_.emplace(config, std::move(fresh));
}

PyramidBuilder& ReliefPrograms::pyramidBuilder() {
    if (!builder_) builder_.emplace(gl_, shaderDir_);
    return *builder_;
}

}  // namespace microrelief
