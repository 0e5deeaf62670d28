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
import {requireSupportedThree} from './three_version.js';

const kBases = {plane: 0, cylinder: 1, ellipsoid: 2};
const kInterpolations = {bilinear: 0, biquadratic: 1};

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
        glue.threeMaterial.replace(/^[ \t]*\/\/ MR_UV_ASSIGNMENTS.*$/m, () => uvAssignments.join('\n'));
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

// The defines every relief material shares: the base and the last level.
function reliefDefines(relief) {
    return {
        MICRORELIEF_BASE: String(kBases[relief.base.kind]),
        MICRORELIEF_INTERPOLATION: String(kInterpolations[relief.interpolation]),
    };
}

// What the relief's materials have in common: attached to one Relief (whose uniforms they
// read), the box drawn from both sides with the faces chosen per draw (mrFaces).
function attach(material, relief) {
    if (material.relief && material.relief !== relief)
        throw new Error('microrelief-three: this material already belongs to another Relief; give each relief its own material');
    material.relief = relief;
    material.side = THREE.DoubleSide;
    material.needsUpdate = true;
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
            this.isReliefMaterial = true;
            this.relief = null;
            this.side = THREE.DoubleSide;
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

        attachRelief(relief) {
            attach(this, relief);
        }

        onBeforeCompile(shader) {
            if (!this.relief) throw new Error(`microrelief-three: a ${name} draws only on a Relief (new Relief(map, {material}))`);
            shader.defines = {...shader.defines, ...reliefDefines(this.relief)};
            if (this.selfShadow) shader.defines.MR_SELF_SHADOW = '';
            if (this.albedoUniform.value) shader.defines.MR_ALBEDO_MAP = '';
            Object.assign(shader.uniforms, this.relief.uniforms, {mrAlbedoMap: this.albedoUniform});
            shader.vertexShader = patchVertex(shader.vertexShader);
            shader.fragmentShader = patchFragment(shader.fragmentShader);
        }

        customProgramCacheKey() {
            const relief = this.relief;
            return `microrelief:${relief ? relief.base.kind + ':' + relief.interpolation : ''}:${this.selfShadow ? 1 : 0}:${this.albedoUniform.value ? 1 : 0}`;
        }

        copy(source) {
            super.copy(source);
            this.albedoUniform = {value: source.albedoUniform ? source.albedoUniform.value : null};
            this.selfShadow = source.selfShadow;
            this.relief = null;
            return this;
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
        super({vertexShader: kShadingVertex, fragmentShader: '', toneMapped: false});
        this.isReliefMaterial = true;
        this.relief = null;
        this.side = THREE.DoubleSide;
        this.shadows = shadows;
        this.uniforms = {
            mrLightDirection: {value: lightDirection.clone()},
            albedo: {value: albedo.clone()},
            albedoMap: {value: albedoMap},
        };
    }

    attachRelief(relief) {
        attach(this, relief);
        this.defines = {
            ...reliefDefines(relief),
            MICRORELIEF_ALBEDO_MAP: this.uniforms.albedoMap.value ? '1' : '0',
            MICRORELIEF_SHADOWS: this.shadows === 'hard' ? '1' : '0',
        };
        Object.assign(this.uniforms, relief.uniforms);
        this.fragmentShader = '#include <common>\n#include <logdepthbuf_pars_fragment>\n' + library + glue.reliefThree + glue.microreliefShading;
    }
}
