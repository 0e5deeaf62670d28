// The compiled programs of one GL context, shared by every relief drawn in it: each
// configuration of the relief program (ReliefShaderConfig: method, base, last level, depth
// layout, shadows, ...) compiled once, on first use, and the pyramid builder's passes
// (gl/PyramidBuilder.h), made on first use. N reliefs in one context (an engine's scene, a
// tool's several maps) hold one ReliefPrograms between them, not N caches: a program is
// compiled once whichever relief asks for it first. microrelief-three splits its
// resources the same way (one ReliefMap, many Relief meshes).
//
// Its GL objects belong to the context `gl` loads: it must not outlive it. Not thread-safe,
// as the context is not.
#pragma once

#include <filesystem>
#include <map>
#include <optional>

#include "microrelief/gl/Objects.h"
#include "microrelief/gl/PyramidBuilder.h"
#include "microrelief/gl/ReliefShader.h"

namespace microrelief {

class ReliefPrograms {
public:
    // `shaderDir` holds relief_box.vert, relief.frag, pyramid/ and microrelief/. Compiles
    // nothing yet.
    ReliefPrograms(const GL& gl, std::filesystem::path shaderDir);
    ReliefPrograms(const ReliefPrograms&) = delete;
    ReliefPrograms& operator=(const ReliefPrograms&) = delete;

    // The program of `config`, compiled on first use and kept (`compiled`, where given, says
    // whether this call compiled it); on a compile failure throws Error(Runtime) (the
    // compiler's log mapped to the files) and keeps nothing new. The reference stays valid
    // until reload().
    ReliefShader& program(const ReliefShaderConfig& config, bool* compiled = nullptr);
    // Compiles `config` from the files again; on failure throws and keeps every program it
    // had. On success the others are dropped, for every relief that shares them (they may
    // be stale), and compiled again when next asked for.
    void reload(const ReliefShaderConfig& config);
    // Programs compiled so far, reloads included.
    int compiled() const { return compiled_; }

    // The GPU pyramid builder of this context, made on first use (throws as its
    // constructor does, and makes it again at the next call).
    PyramidBuilder& pyramidBuilder();

    const GL& gl() const { return gl_; }
    const std::filesystem::path& shaderDir() const { return shaderDir_; }

private:
    const GL& gl_;
    std::filesystem::path shaderDir_;
    std::map<ReliefShaderConfig, ReliefShader> programs_;
    std::optional<PyramidBuilder> builder_;
    int compiled_ = 0;
};

}  // namespace microrelief
