// coarse_start.frag: the coarse pass (microrelief/coarse_start.glsl), one fragment per tile
// of MICRORELIEF_COARSE_TILE x MICRORELIEF_COARSE_TILE pixels of the drawn picture (or
// picture tile: ReliefRenderer's viewport is ceil(width / T) x ceil(height / T)), drawn
// with pyramid/pass.vert. Writes the distance t from which the tile's pixels trace
// (relief.frag reads it with the same define) and the pyramid texels the tile read. The
// plane base and the multilevel method's windows on unit 2 (ReliefShader's unit).
#include "microrelief/variants.glsl"
#include "microrelief/coarse_start.glsl"
#include "relief_parameters.glsl"

#ifndef MICRORELIEF_COARSE_TILE
#define MICRORELIEF_COARSE_TILE 8
#endif

uniform sampler2D windowPyramid;

layout(location = 0) out vec4 outStart;  // x: the start (MR_COARSE_KEEP, MR_COARSE_MISS or t), y: texels read, z: the first segment's length

// The direction of the ray through pixel centre `centre` of the drawn picture, as
// relief.frag casts it.
vec3 pixelDirection(vec2 centre) {
    vec2 ndc = (centre + tileOrigin) / viewportSize * 2.0 - 1.0;
    return cameraForward + ndc.x * cameraRight + ndc.y * cameraUp;
}

void main() {
    mr_Relief relief = mr_Relief(mr_ReliefMap(reliefSize, pyramidSize, pyramidLevels, reliefMaxHeight, reliefTiles),
                                 mr_ReliefPlacement(objectToWorld, worldToObject, heightScale, frameScale));
    // The tile's first and last pixel centres (the last row and column clipped to the
    // drawn picture, whose size the viewport's tiles cover): every pixel centre of the
    // tile lies in their rectangle.
    ivec2 tile = ivec2(gl_FragCoord.xy);
    vec2 drawn = ceil(viewportSize - tileOrigin);
    vec2 first = vec2(tile * MICRORELIEF_COARSE_TILE) + 0.5;
    vec2 last = min(first + float(MICRORELIEF_COARSE_TILE - 1), drawn - 0.5);
    vec3 d[4];
    d[0] = mr_baseFrameVector(relief, pixelDirection(first));
    d[1] = mr_baseFrameVector(relief, pixelDirection(vec2(last.x, first.y)));
    d[2] = mr_baseFrameVector(relief, pixelDirection(vec2(first.x, last.y)));
    d[3] = mr_baseFrameVector(relief, pixelDirection(last));
    int reads;
    float leafLength;
    float start = mr_coarseStart(relief, windowPyramid, mr_baseFramePoint(relief, eye), d, tMin, tMax, reads, leafLength);
    outStart = vec4(start, float(reads), leafLength, 1.0);
}
