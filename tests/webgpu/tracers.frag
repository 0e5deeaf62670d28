// tracers.frag: every tracer of the library in one WGSL module, compiled, not drawn, by
// glsl_wgsl_equal.py (naga keeps every function, and Chromium's WebGPU checks each one): the
// multilevel tracer that entry.frag draws and the peers beside it (maxmip, cone stepping,
// relaxed cones, the parallax family), so that a construct WGSL refuses in a file entry.frag
// does not include (two out arguments into one variable: Tint's "invalid aliased pointer
// argument") fails the suite too. The reads through the package's WebGPU hooks
// (scripts/wgsl.mjs: samplerless texelFetch), the relaxed cones' filtered read through a
// sampler. Only with VULKAN defined (translate.mjs --wgsl).
#extension GL_EXT_samplerless_texture_functions : require
layout(set = 0, binding = 0) uniform sampler mrNearest;
#define MICRORELIEF_SAMPLER texture2D
#define MICRORELIEF_TEXTURE_GATHER 0
#define MICRORELIEF_READ_SAMPLE(heights, texel) texelFetch(heights, texel, 0).r
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) texelFetch(pyramid, texel, level).r
#define MICRORELIEF_READ_RELAXED_CONE(cones, p, size) textureLod(sampler2D(cones, mrNearest), (p) / (size), 0.0).rg
#define MICRORELIEF_ALBEDO_TEXTURE texture2D
#define MICRORELIEF_ALBEDO_SAMPLED(t) sampler2D(t, mrNearest)
#include "microrelief/map_space.glsl"
#include "microrelief/multilevel_trace.glsl"
#include "microrelief/maxmip_trace.glsl"
#include "microrelief/cone_step.glsl"
#include "microrelief/relaxed_cone_step.glsl"
#include "microrelief/normal_mapping.glsl"
#include "microrelief/parallax_occlusion.glsl"
#include "microrelief/parallax_offset.glsl"
#include "microrelief/relief_mapping.glsl"
#include "microrelief/steep_parallax.glsl"
#include "microrelief/shading.glsl"
#include "microrelief/shadow.glsl"
#include "microrelief/albedo.glsl"

void main() {}
