// Declarations of checks.js (hand-written; tests/three's typecheck holds them to the module).
import type {ReliefInterpolation} from './relief.js';

type Triple = [number, number, number];

/** The pages' names for the scene's fields (their URL keys), as the checks' messages use them. */
export const kFieldNames: Readonly<Record<string, string>>;

/** A view as the pages hold it; any field left out is microrelief-render's default. */
export interface SceneView {
    eye: Triple;
    target: Triple;
    up?: Triple;
    fovy?: number;
    heightScale?: number;
    base?: string;
    radius?: number;
    length?: number;
    radii?: Triple;
    interpolation?: ReliefInterpolation;
    /** 12 numbers: --model's three rows. */
    model?: number[];
    method?: string;
    steps?: number;
    pixelError?: number;
    light?: Triple;
    shadows?: string;
    lightSize?: number;
    view?: string;
    background?: Triple;
}

/** A map's size and top, for the float limits. */
export interface SceneMap {
    width: number;
    height: number;
    maxHeight: number;
    name: string;
}

/** microrelief-render's own checks of a scene, compiled to WebAssembly (loadSceneChecks). */
export class SceneChecks {
    /** From emscripten's module factory. */
    static load(createModule: () => Promise<unknown>): Promise<SceneChecks>;
    constructor(module: unknown);
    /** '' where microrelief-render would draw `view`, else its message (one line). */
    refusal(view: SceneView, map?: SceneMap | null, pixels?: [number, number] | null): string;
    /** The fields a message may name that have no name here. */
    unnamedFields(): string[];
}

/** The checks, once their WebAssembly is instantiated; rejects, saying so, in a package packed without it. */
export function loadSceneChecks(): Promise<SceneChecks>;
