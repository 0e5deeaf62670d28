// relief_parameters.glsl: the uniform block of the program's own shaders (relief_box.vert,
// relief.frag): the camera, the relief's map and placement, the method's settings and the
// shading, in one std140 block that the host fills with one buffer update per draw. The
// C++ mirror is ReliefParameters (include/microrelief/gl/ReliefShader.h); a GL test holds
// the two to the same offsets. Members are ordered so that a vec3 is followed by the
// scalar that fills its 16-byte slot, and pairs of vec2 share one.
layout(std140) uniform MicroreliefParameters {
    // "World" here is the shader's world: the renderer's world moved by -eye (it traces
    // relative to the eye, ReliefRenderer::parameters), so eye is 0 and a relief far
    // from the world's origin keeps its precision.
    mat4 viewProjection;  // world -> the caller's clip space (a tile's, for tiled pictures)
    mat4 objectToWorld;   // the model transform (mr_ReliefPlacement), then -eye
    mat4 worldToObject;   // its inverse
    vec3 eye;             // the camera in that world: 0 from the renderer
    float pixelErrorTolerance;  // multilevel: stop at windows narrower than this many pixels
    vec3 cameraRight;     // scaled by tan(fovx / 2)
    float heightScale;    // s: object height of map height 1 (plane); radius fraction (curved)
    vec3 cameraUp;        // scaled by tan(fovy / 2)
    float reliefMaxHeight;  // the pyramid's top texel, map units
    vec3 cameraForward;   // unit
    float tMin;           // the rays' range (mr_RayQuery): 0 and MR_T_INFINITY for a picture
    vec3 frameScale;      // curved bases: object size of the canonical frame's unit
    float tMax;
    vec3 reliefBoxMin;    // the proxy box, object space
    int pyramidLevels;
    vec3 reliefBoxMax;
    int maxIterations;
    vec3 lightDirection;  // towards the light, world, unit
    int debugView;        // MR_DEBUG_VIEW_*; 0 is the shaded picture
    vec3 albedo;          // linear
    int methodSteps;      // peers' quality knob: layers, samples or linear steps
    vec2 reliefSize;      // W, H (tiled N x M: N W, M H)
    ivec2 pyramidSize;    // the finest level's size: a tile's W, H (windows); maxmip W, H rounded up to powers of two
    vec2 viewportSize;    // the whole picture's, in pixels
    vec2 tileOrigin;      // where the drawn tile sits in it (0, 0: the whole picture)
    int methodMinSteps;   // pom: samples when looking straight down
    int methodRefineSteps;  // relief: binary search steps
    int depthZeroToOne;   // 1: clip-space depth in [0, 1] (glClipControl), 0: [-1, 1]
    int blockPadding;     // std140 padding: lightPosition starts a 16-byte row; hosts write 0
    vec4 lightPosition;   // xyz: a point light, world; w: 1 for it, 0 for lightDirection's
    float lightTanRadius;  // soft shadows: tan of the light's angular radius
    int albedoFinest;     // 1: the albedo's finest level only (no filtering; tests compare)
    ivec2 reliefTiles;    // N, M: the map repeated N x M times (reliefSize is the whole)
};
