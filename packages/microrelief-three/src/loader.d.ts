// Declarations of loader.js (hand-written; tests/three's typecheck holds them to the module).
import {Loader} from 'three';
import type {LoadingManager, WebGLRenderer} from 'three';

import type {ReliefMap, ReliefMapOptions} from './pyramid.js';

export interface ReliefMapLoaderOptions extends ReliefMapOptions {
    /** The PNG channel the heights are read from (0: red or grey). Default 0. */
    channel?: number;
}

/**
 * A height map loaded as three loads its assets (three's FileLoader: the manager's progress, setPath,
 * setRequestHeader, setWithCredentials, THREE.Cache) into a ReliefMap for `renderer`; a PNG decoded
 * exactly (16 bits kept). Errors: one HeightMapError or ReliefGpuError naming the URL and the reason.
 */
export class ReliefMapLoader extends Loader<ReliefMap> {
    constructor(renderer: WebGLRenderer, manager?: LoadingManager);
    renderer: WebGLRenderer;
    options: ReliefMapLoaderOptions;
    /** createReliefMap's options (wrapU, pyramid) and the PNG channel; those left out are kept. */
    setOptions(options: ReliefMapLoaderOptions): this;
}
