// present.frag: the web page's last pass (web/relief_gl.js). relief.frag writes linear
// colour into an SRGB8_ALPHA8 target, which the GL encodes as microrelief-render's target
// does; a WebGL canvas is not sRGB, so this pass reads the target back (the sampler decodes
// it to linear) and writes it encoded again. The round trip in float moves an 8-bit value
// by far less than half a level, so the canvas holds the target's bytes.
#include "../microrelief/shading.glsl"

uniform sampler2D picture;  // the relief's target, the canvas's size

layout(location = 0) out vec4 color;

void main() {
    vec3 linear = texelFetch(picture, ivec2(gl_FragCoord.xy), 0).rgb;
    color = vec4(mr_encodeSrgb(linear), 1.0);
}
