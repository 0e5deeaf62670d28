// mesh_relief.vert: the mesh base's proxy (core/base/MeshProxy.h): each proxy triangle of a
// prism's hull, carrying its mesh triangle's index flat, so that every ray through the
// shell gets a fragment of each prism it may meet (mesh_relief.frag traces it there).
layout(location = 0) in vec3 position;      // the mesh's units
layout(location = 1) in uint meshTriangle;  // MeshProxy::meshTriangles

uniform mat4 mr_viewProjection;  // mesh units to clip space

out vec3 mr_proxyPoint;
flat out uint mr_meshTriangleIndex;

void main() {
    mr_proxyPoint = position;
    mr_meshTriangleIndex = meshTriangle;
    gl_Position = mr_viewProjection * vec4(position, 1.0);
}
