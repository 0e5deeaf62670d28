// relief_box.vert: the proxy geometry, the relief's bounding box in world space. Each
// fragment of its back faces (drawn with front faces culled, so that the eye may be
// inside the box) casts its own ray in relief.frag.
layout(location = 0) in vec3 boxCorner;

uniform mat4 viewProjection;

void main() { gl_Position = viewProjection * vec4(boxCorner, 1.0); }
