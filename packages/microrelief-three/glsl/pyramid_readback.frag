// pyramid_readback.frag: the texels of one level of an R16F or R32F texture as the bits of
// their floats in an RGBA8 target (src/pyramid.js): the top of the windows pyramid, which
// settles S, and whole levels for the tests, exactly, without a float render target.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D source;
uniform int level;

layout(location = 0) out vec4 packedFloat;

void main() {
    uint bits = floatBitsToUint(texelFetch(source, ivec2(gl_FragCoord.xy), level).r);
    packedFloat = vec4(float(bits & 255u), float((bits >> 8u) & 255u), float((bits >> 16u) & 255u), float(bits >> 24u)) / 255.0;
}
