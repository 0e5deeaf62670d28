// pass.vert: one triangle that covers the viewport, for the pyramid builder's passes
// (gl/PyramidBuilder.h). No vertex data: the corners come from gl_VertexID. The viewport
// is the rectangle of texels a pass computes; gl_FragCoord names each texel.
void main() {
    vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1));
    gl_Position = vec4(corner - 1.0, 0.0, 1.0);
}
