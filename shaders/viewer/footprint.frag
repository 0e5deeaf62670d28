// footprint.frag: the brush ring's colour, into the picture (the viewer's offscreen
// target; its AOV and statistics outputs are left as they are).
uniform vec4 colour;

layout(location = 0) out vec4 picture;

void main() { picture = colour; }
