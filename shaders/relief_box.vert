// relief_box.vert: the proxy geometry, the relief's bounding box in object space, placed by
// the model transform. Each fragment of its front faces (its back faces when the eye is
// inside the box) casts its own ray in relief.frag.
#include "relief_parameters.glsl"

layout(location = 0) in vec3 boxCorner;

void main() { gl_Position = viewProjection * (objectToWorld * vec4(boxCorner, 1.0)); }
