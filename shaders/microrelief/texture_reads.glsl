// texture_reads.glsl: every texture read of the library, each through a macro with a
// default, so that a host reads its own way (texture arrays, bindless handles, its own
// addressing) by defining the macro before the first include, without forking a file (as
// LYGIA's SAMPLER_FNC and SAMPLER_TYPE). The library's functions take their textures as
// MICRORELIEF_SAMPLER and never read them but through these:
//  * MICRORELIEF_READ_SAMPLE(heights, texel): the height sample at integer texel `texel`
//    (ivec2, inside the texture; mr_sampleTexel clamps, wraps and tiles) of level 0;
//  * MICRORELIEF_GATHER_SAMPLES(heights, uv): the 2 x 2 samples whose centres surround the
//    texture point `uv` (in [0, 1]^2), in textureGather's order (i0, j1), (i1, j1),
//    (i1, j0), (i0, j0); used where MICRORELIEF_TEXTURE_GATHER is 1;
//  * MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize): a max pyramid's texel
//    `texel` of mip level `level` (levelSize: that level's size, vec2), nearest filtering.
// Each read is counted as one fetch (fetch_count.glsl) by the function that makes it.
// (One line each: GLSL before 4.20 has no line continuation.)
#ifndef MICRORELIEF_TEXTURE_READS_GLSL
#define MICRORELIEF_TEXTURE_READS_GLSL

#include "precision.glsl"

#ifndef MICRORELIEF_SAMPLER
#define MICRORELIEF_SAMPLER sampler2D
#endif

// How a cell's four samples are read: 1, one gather (GLSL 4.00, ES 3.10 and up); 0, four
// single reads.
#ifndef MICRORELIEF_TEXTURE_GATHER
#if (!defined(GL_ES) && __VERSION__ >= 400) || (defined(GL_ES) && __VERSION__ >= 310)
#define MICRORELIEF_TEXTURE_GATHER 1
#else
#define MICRORELIEF_TEXTURE_GATHER 0
#endif
#endif

// How a pyramid texel is read by default. 0: textureLod at the texel's centre with nearest
// filtering, the ordinary texture path, as the paper has it ("the same mechanism as for
// the usual texture"). 1: texelFetch of the same texel, which skips the sampler's
// coordinate work (a quarter faster on llvmpipe; the same on most GPUs).
#ifndef MICRORELIEF_PYRAMID_TEXEL_FETCH
#define MICRORELIEF_PYRAMID_TEXEL_FETCH 0
#endif

#ifndef MICRORELIEF_READ_SAMPLE
#define MICRORELIEF_READ_SAMPLE(heights, texel) texelFetch(heights, texel, 0).r
#endif

#ifndef MICRORELIEF_GATHER_SAMPLES
#define MICRORELIEF_GATHER_SAMPLES(heights, uv) textureGather(heights, uv)
#endif

#ifndef MICRORELIEF_READ_PYRAMID
#if MICRORELIEF_PYRAMID_TEXEL_FETCH
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) texelFetch(pyramid, texel, level).r
#else
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) textureLod(pyramid, (vec2(texel) + 0.5) / (levelSize), float(level)).r
#endif
#endif

#endif
