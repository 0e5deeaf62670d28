// precision.glsl: the precision the library needs, stated where GLSL ES asks for one.
//
// A GLSL ES 3.00 fragment shader has no default float precision, and defaults int and
// uint to mediump (a range of +-2^15 is all that guarantees) and sampler2D to lowp. The
// library needs more: segments are named by 24-bit indices along the root, shifted as
// uint (segment_walk.glsl, MICRORELIEF_MAX_DEPTH); texel coordinates reach 16384 in
// int; heights, ray parameters and the R32F texels it reads need full float precision.
// So it declares highp for all three. Desktop GLSL ignores precision, so this costs
// nothing there. The statements hold to the end of the including shader: a host that
// wants lower defaults for its own code states them after the include.
#ifndef MICRORELIEF_PRECISION_GLSL
#define MICRORELIEF_PRECISION_GLSL

#ifdef GL_ES
precision highp float;
precision highp int;
precision highp sampler2D;
#endif

#endif
