// footprint.vert: the sculpting brush's ring on the relief (microrelief-viewer), a line
// loop of world positions on the surface, drawn over the relief with its depth.
uniform mat4 viewProjection;

layout(location = 0) in vec3 position;

void main() { gl_Position = viewProjection * vec4(position, 1.0); }
