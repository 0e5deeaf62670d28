// materials.js: three.js's own materials, tracing the relief per pixel before they shade.
//
// ReliefStandardMaterial and ReliefPhysicalMaterial are MeshStandardMaterial and
// MeshPhysicalMaterial: three's lights, environment maps, fog, tone mapping, colour
// management, shadow maps and every map they take, evaluated at the traced hit. Their
// shaders are three's, patched in onBeforeCompile (patchFragment below): the varyings
// three computes per vertex become globals that mrBeginPixel() (glsl/three_material.glsl)
// sets from the hit, the tangent frame comes from the map's axes, gl_FragDepth is the hit's.
// ReliefDepthMaterial and ReliefDistanceMaterial do the same for three's shadow maps
// (directional and spot lights; point lights), tracing from the light's camera.
// ReliefShadingMaterial is the library's own shading (microrelief-render's picture).
import * as THREE from 'three';

import {glue, library} from '../generated/glsl.js';
import {defineValue, kBaseKindValues, kInterpolationValues, kShadowModeValues} from '../generated/relief_layout.js';
import {requireSupportedThree} from './three_version.js';

// three's #include <chunk>, resolved as three resolves them (so that what follows can see
// the whole shader).
function resolveIncludes(source) {
    return source.replace(/^[ \t]*#include +<([\w\d./]+)>/gm, (whole, name) => {
        const chunk = THREE.ShaderChunk[name];
        if (chunk === undefined) throw new Error(`microrelief-three: cannot resolve #include <${name}>`);
        return resolveIncludes(chunk);
    });
}

// Uniforms three declares for its vertex shader only, which the fragment needs once the
// varying that carried them is computed per pixel.
const kVertexUniforms = {
    vDirectionalShadowCoord: 'uniform mat4 directionalShadowMatrix[ NUM_DIR_LIGHT_SHADOWS ];',
    vPointShadowCoord: 'uniform mat4 pointShadowMatrix[ NUM_POINT_LIGHT_SHADOWS ];',
    vSpotLightCoord: 'uniform mat4 spotLightMatrix[ NUM_SPOT_LIGHT_COORDS ];',
};

// Every varying three's fragment shader reads becomes a global with MR_HAS_<name> defined
// beside it; a uv varying also gets its assignment from the hit's uv through its map's
// transform (three's uv_vertex). Returns the patched source and the uv assignments.
function varyingsToGlobals(source) {
    const uvAssignments = [];
    const patched = source.replace(/^([ \t]*)varying\s+(\w+)\s+(v\w+)\s*(\[[^\]]*\])?\s*;/gm, (whole, indent, type, name, array = '') => {
        let extra = kVertexUniforms[name] && !source.includes(kVertexUniforms[name]) ? `\n${indent}${kVertexUniforms[name]}` : '';
        const uv = /^v(\w*)Uv$/.exec(name);
        if (uv && type === 'vec2') {
            if (name === 'vUv') {
                uvAssignments.push(`#ifdef MR_HAS_vUv\n    vUv = mrHitPixel.uv;\n#endif`);
            } else {
                const transform = uv[1][0].toLowerCase() + uv[1].slice(1) + 'Transform';
                if (!new RegExp(`uniform\\s+mat3\\s+${transform}\\s*;`).test(source)) extra += `\n${indent}uniform mat3 ${transform};`;
                uvAssignments.push(`#ifdef MR_HAS_${name}\n    ${name} = (${transform} * vec3(mrHitPixel.uv, 1.0)).xy;\n#endif`);
            }
        }
        return `${indent}${type} ${name}${array};${extra}\n${indent}#define MR_HAS_${name}`;
    });
    return {patched, uvAssignments};
}

// The relief's GLSL for three's own fragment shaders: the library, then the glue.
function reliefPrelude(uvAssignments) {
    return library + glue.reliefThree +
        glue.threeMaterial.replace(/^[ \t]*MR_UV_ASSIGNMENTS\b.*$/m, () => uvAssignments.join('\n'));
}

function replaceOnce(source, pattern, replacement, what) {
    if (!pattern.test(source)) throw new Error(`microrelief-three: this three.js has no ${what} where the relief expects it (a three.js outside the tested range?)`);
    return source.replace(pattern, replacement);
}

// A three.js fragment shader made to trace the relief before it shades.
export function patchFragment(fragmentShader) {
    const {patched, uvAssignments} = varyingsToGlobals(resolveIncludes(fragmentShader));
    let source = patched;
    source = replaceOnce(source, /\bvoid\s+main\s*\(\s*\)\s*\{/, (m) => reliefPrelude(uvAssignments) + '\n' + m + '\n    mrBeginPixel();', 'main()');
    // The hit's normal is the normal, whichever face of the box ran.
    source = source.replace(/float\s+faceDirection\s*=\s*gl_FrontFacing\s*\?\s*1\.0\s*:\s*-\s*1\.0\s*;/g, 'float faceDirection = 1.0;');
    source = source.replace(/getTangentFrame\(\s*-\s*vViewPosition\s*,\s*normal\s*,/g, 'mrTangentFrame( normal,');
    // mrBeginPixel wrote the depth, logarithmic where three's buffer is.
    source = source.replace(/gl_FragDepth\s*=\s*vIsPerspective[^;]*;/g, '');
    // The library's exact self-shadow after three's light setup (MR_SELF_SHADOW).
    source = source.replace(/(get(Directional|Sun)LightInfo\(\s*(\w+)\s*,\s*directLight\s*\);)/g,
                            '$1\n\t\tdirectLight.color *= mrSelfShadowDirection( $3.direction );');
    source = source.replace(/(get(Point|Spot)LightInfo\(\s*(\w+)\s*,\s*geometryPosition\s*,\s*directLight\s*\);)/g,
                            '$1\n\t\tdirectLight.color *= mrSelfShadowPoint( $3.position );');
    // The map's colours (MR_ALBEDO_MAP), as relief.frag filters them.
    source = source.replace(/(vec4\s+diffuseColor\s*=\s*vec4\(\s*diffuse\s*,\s*opacity\s*\)\s*;)/,
                            '$1\n#ifdef MR_ALBEDO_MAP\n\tdiffuseColor.rgb *= mrSurfaceAlbedo();\n#endif');
    // Never silent: an exhausted traversal shows magenta, as in relief.frag.
    const end = source.lastIndexOf('}');
    source = source.slice(0, end) + '\tif ( mrExhausted ) gl_FragColor = vec4( 1.0, 0.0, 1.0, 1.0 );\n' + source.slice(end);
    return source;
}

// The box's vertex shader, with its clip position passed on (mrClip).
export function patchVertex(vertexShader) {
    let source = replaceOnce(vertexShader, /\bvoid\s+main\s*\(\s*\)\s*\{/, (m) => 'varying vec4 mrClip;\n' + m, 'main()');
    const end = source.lastIndexOf('}');
    return source.slice(0, end) + '\tmrClip = gl_Position;\n' + source.slice(end);
}

// The defines every relief program shares (the materials here, override.js's equivalents,
// the picks' program): the base and the last level, each value by its name from the
// library's own table (variants.glsl, through the generated relief_layout.js).
export function reliefDefines(relief) {
    return {
        MICRORELIEF_BASE: defineValue(kBaseKindValues, relief.base.kind, 'MICRORELIEF_BASE'),
        MICRORELIEF_INTERPOLATION: defineValue(kInterpolationValues, relief.interpolation, 'MICRORELIEF_INTERPOLATION'),
    };
}

// The program variant a relief needs: its base and its last level.
function reliefVariant(relief) {
    return relief ? `${relief.base.kind}:${relief.interpolation}` : '';
}

// One material, many reliefs. A relief's own uniforms (its map's textures and sizes, its
// height scale, this draw's rays and matrices: Relief.uniforms) are not the material's, yet
// three uploads a material's uniforms only when the program or the material changes between
// two draws (and at the first draw of each render). Two ways were weighed:
//   - a per-relief instance derived from the shared material, kept in step by its version:
//     three then sees another material for each relief and uploads on each switch, but the
//     relief draws with a material that is not the one assigned (relief.material would have
//     to answer with the instance, or three would draw the shared one);
//   - uniforms resolved per draw (chosen): the material's relief uniforms are getters that
//     read the relief it is about to draw (`material.relief`, set in onBeforeRender below,
//     which three calls between the object's onBeforeRender and the draw), and where that
//     relief is another than the last one drawn with it, the bound program is let go
//     (renderer.state.useProgram(null)) so that three's setProgram binds it again and
//     uploads every uniform, as on a change of material.
// Both cost the same upload per switch (three's own per-uniform caches skip the values that
// did not change); measured on SwiftShader (tests/three/objects.js, uniformCalls): two
// reliefs drawn with one material make the same number of gl.uniform* calls a frame as two
// with a material each. The chosen way keeps relief.material the object assigned, as a
// three.js mesh does. Reliefs of different bases or last levels sharing one material
// switch programs at each switch (material.needsUpdate: three finds the compiled variant in
// its cache, one compile each).
function reliefUniformSlots(material, relief) {
    const slots = {};
    for (const name of Object.keys(relief.uniforms)) {
        slots[name] = {get value() {
            return material.relief.uniforms[name].value;
        }};
    }
    return slots;
}

// Called by three before each draw of `object` with `material`.
function drawRelief(material, name, renderer, object) {
    if (!object.isRelief) throw new Error(`microrelief-three: a ${name} draws only on a Relief (new Relief(map, {material}) or relief.material = ...)`);
    if (material.relief !== object) {
        material.relief = object;
        renderer.state.useProgram(null);  // three uploads this relief's uniforms (above)
    }
    const variant = reliefVariant(object);
    if (material.reliefVariant !== variant) {
        if (material.reliefVariant !== undefined) material.needsUpdate = true;
        material.reliefVariant = variant;
    }
}

// What the relief's materials have in common: drawn from both sides of the box, the faces
// chosen per draw (mrFaces); any number of reliefs may share one.
function initReliefMaterial(material) {
    material.isReliefMaterial = true;
    material.relief = null;  // the Relief it draws next (the last one drawn or given it)
    material.reliefVariant = undefined;
    material.side = THREE.DoubleSide;
}

// ReliefStandardMaterial and ReliefPhysicalMaterial: three's MeshStandardMaterial and
// MeshPhysicalMaterial with two more parameters, `albedoMap` (the map's colours, as
// relief.frag filters them over the pixel's footprint: a texture with flipY false, row 0 of
// the image at the map's row 0; loadAlbedo makes one) and `selfShadow` (the library's exact
// hard shadow for three's directional, point and spot lights, on top of three's shadow maps).
function reliefMaterial(Base, name) {
    return class extends Base {
        constructor(parameters = {}) {
            requireSupportedThree();
            const {albedoMap = null, selfShadow = false, ...rest} = parameters;
            super(rest);
            initReliefMaterial(this);
            this.shadowSide = THREE.DoubleSide;  // the depth materials choose faces per draw too
            this.albedoUniform = {value: albedoMap};
            this.selfShadow = selfShadow;
        }

        get albedoMap() {
            return this.albedoUniform.value;
        }

        set albedoMap(texture) {
            if ((texture === null) !== (this.albedoUniform.value === null)) this.needsUpdate = true;
            this.albedoUniform.value = texture;
        }

        onBeforeRender(renderer, scene, camera, geometry, object) {
            drawRelief(this, name, renderer, object);
        }

        onBeforeCompile(shader) {
            if (!this.relief) throw new Error(`microrelief-three: a ${name} draws only on a Relief (new Relief(map, {material}) or relief.material = ...)`);
            shader.defines = {...shader.defines, ...reliefDefines(this.relief)};
            if (this.selfShadow) shader.defines.MR_SELF_SHADOW = '';
            if (this.albedoUniform.value) shader.defines.MR_ALBEDO_MAP = '';
            Object.assign(shader.uniforms, reliefUniformSlots(this, this.relief), {mrAlbedoMap: this.albedoUniform});
            shader.vertexShader = patchVertex(shader.vertexShader);
            shader.fragmentShader = patchFragment(shader.fragmentShader);
        }

        customProgramCacheKey() {
            return `microrelief:${reliefVariant(this.relief)}:${this.selfShadow ? 1 : 0}:${this.albedoUniform.value ? 1 : 0}`;
        }

        // Also from three's own MeshStandardMaterial or MeshPhysicalMaterial (the way to
        // give a Relief one: new ReliefStandardMaterial().copy(material)).
        copy(source) {
            super.copy(source);
            this.albedoUniform.value = source.isReliefMaterial ? source.albedoUniform.value : null;
            this.selfShadow = source.isReliefMaterial ? source.selfShadow : false;
            return this;
        }

        // three's own record (ObjectLoader reads it as a MeshStandardMaterial or
        // MeshPhysicalMaterial), the relief's parameters in userData (Relief.fromMesh).
        toJSON(meta) {
            const data = super.toJSON(meta);
            data.userData = {...data.userData, microrelief: {type: name, selfShadow: this.selfShadow}};
            return data;
        }
    };
}

export const ReliefStandardMaterial = reliefMaterial(THREE.MeshStandardMaterial, 'ReliefStandardMaterial');
export const ReliefPhysicalMaterial = reliefMaterial(THREE.MeshPhysicalMaterial, 'ReliefPhysicalMaterial');

// The relief's depth from a light's camera, for three's shadow maps: MeshDepthMaterial
// (directional and spot lights) and MeshDistanceMaterial (point lights), tracing the ray of
// each shadow-map texel (Relief sets them as customDepthMaterial and customDistanceMaterial).
function reliefShadowMaterial(Base, name, parameters) {
    return class extends Base {
        constructor(relief) {
            super(parameters);
            this.relief = relief;
        }

        onBeforeCompile(shader) {
            shader.defines = {...shader.defines, ...reliefDefines(this.relief), MR_SHADOW_PASS: ''};
            Object.assign(shader.uniforms, this.relief.uniforms);
            shader.vertexShader = patchVertex(shader.vertexShader);
            shader.fragmentShader = patchFragment(shader.fragmentShader);
        }

        customProgramCacheKey() {
            return `microrelief:${this.relief.base.kind}:${this.relief.interpolation}`;
        }
    };
}

export const ReliefDepthMaterial = reliefShadowMaterial(THREE.MeshDepthMaterial, 'ReliefDepthMaterial', {depthPacking: THREE.RGBADepthPacking});
export const ReliefDistanceMaterial = reliefShadowMaterial(THREE.MeshDistanceMaterial, 'ReliefDistanceMaterial', {});

const kShadingFragment = '#include <common>\n#include <logdepthbuf_pars_fragment>\n' + library + glue.reliefThree + glue.microreliefShading;

const kShadingVertex = `
varying vec4 mrClip;
void main() {
    gl_Position = projectionMatrix * modelViewMatrix * vec4( position, 1.0 );
    mrClip = gl_Position;
}
`;

// The library's own shading, as microrelief-render draws it (relief.frag's shaded view):
// one directional light (`lightDirection`, world, towards the light), the map's albedo
// (`albedoMap`, flipY false) or a grey (`albedo`, linear), the hard self-shadow with
// `shadows: 'hard'`. Not lit by three's lights; three's colour management converts its
// linear output. microrelief-render's picture of the same camera, within rounding.
export class ReliefShadingMaterial extends THREE.ShaderMaterial {
    constructor({lightDirection = new THREE.Vector3(-0.45, 0.8, -0.35).normalize(), albedoMap = null,
                 albedo = new THREE.Color(0.6, 0.58, 0.55), shadows = 'off'} = {}) {
        requireSupportedThree();
        if (!['off', 'hard'].includes(shadows)) throw new TypeError(`ReliefShadingMaterial: shadows '${shadows}' (expected off or hard)`);
        super({vertexShader: kShadingVertex, fragmentShader: kShadingFragment, toneMapped: false});
        initReliefMaterial(this);
        this.shadows = shadows;
        this.uniforms = {
            mrLightDirection: {value: lightDirection.clone()},
            albedo: {value: albedo.clone()},
            albedoMap: {value: albedoMap},
        };
    }

    onBeforeRender(renderer, scene, camera, geometry, object) {
        drawRelief(this, 'ReliefShadingMaterial', renderer, object);
    }

    // The relief's uniforms beside the material's own (not in this.uniforms, which clone,
    // copy and toJSON see).
    onBeforeCompile(shader) {
        if (!this.relief) throw new Error('microrelief-three: a ReliefShadingMaterial draws only on a Relief (new Relief(map, {material}) or relief.material = ...)');
        shader.defines = {
            ...shader.defines,
            ...reliefDefines(this.relief),
            MICRORELIEF_ALBEDO_MAP: this.uniforms.albedoMap.value ? '1' : '0',
            MICRORELIEF_SHADOWS: defineValue(kShadowModeValues, this.shadows, 'MICRORELIEF_SHADOWS'),
        };
        shader.uniforms = {...shader.uniforms, ...reliefUniformSlots(this, this.relief)};
    }

    customProgramCacheKey() {
        return `microrelief-shading:${reliefVariant(this.relief)}:${this.shadows}:${this.uniforms.albedoMap.value ? 1 : 0}`;
    }

    copy(source) {
        super.copy(source);
        this.shadows = source.shadows;
        return this;
    }

    // Material's record, not ShaderMaterial's (whose shaders are the package's, 200 kB, and
    // draw nothing without a relief); the parameters in userData (Relief.fromMesh).
    toJSON(meta) {
        const data = THREE.Material.prototype.toJSON.call(this, meta);
        data.userData = {...data.userData, microrelief: {type: 'ReliefShadingMaterial', shadows: this.shadows,
                                                         lightDirection: this.uniforms.mrLightDirection.value.toArray(),
                                                         albedo: this.uniforms.albedo.value.toArray()}};
        return data;
    }
}
