// loader.js: ReliefMapLoader, a height map loaded the way three.js loads its assets (a
// THREE.Loader: a LoadingManager, setPath, setRequestHeader, setWithCredentials, progress,
// load and loadAsync) into a ReliefMap for one renderer.
//
// The file is fetched by three's own FileLoader (responseType 'arraybuffer'), so the
// manager's itemStart/itemEnd/onProgress, its URL modifier and abort, and three's Cache
// (THREE.Cache.enabled) see it as they see any other asset; its bytes are then decoded as
// loadHeights decodes them (heights.js: a PNG by the project's own decoder, 16 bits kept;
// another format through the browser, 8 bits) and made into textures by createReliefMap
// with the loader's options (wrapU, pyramid). The manager counts the item done only once
// the ReliefMap is made. Bad input (a failed request, bytes that are no height map, a map
// the GPU cannot take) is one Error (HeightMapError or ReliefGpuError) whose message is one
// line naming the URL and the reason, handed to onError (loadAsync: rejected with it), and
// the manager's onError is called with the URL.
import * as THREE from 'three';

import {heightsFromBytes, HeightMapError} from './heights.js';
import {createReliefMap} from './pyramid.js';

// The reason a FileLoader's request failed, in heights.js's words.
function readError(name, error) {
    const status = error && error.response && error.response.status;
    return new HeightMapError(`${name}: cannot be read (${status ? `HTTP ${status}` : error && error.message ? error.message : String(error)})`);
}

export class ReliefMapLoader extends THREE.Loader {
    // `renderer`: the WebGLRenderer the ReliefMap's textures are for. `manager`: three's
    // LoadingManager (THREE.DefaultLoadingManager if left out).
    constructor(renderer, manager) {
        super(manager);
        this.renderer = renderer;
        this.options = {wrapU: false, pyramid: 'auto', channel: 0};
    }

    // createReliefMap's options (wrapU, pyramid) and the PNG channel the heights are read
    // from (channel, 0 by default); unnamed ones are kept.
    setOptions(options) {
        this.options = {...this.options, ...options};
        return this;
    }

    load(url, onLoad, onProgress, onError) {
        if (url === undefined) url = '';
        const name = this.manager.resolveURL((this.path ?? '') + url);
        const files = new THREE.FileLoader(this.manager);
        files.setPath(this.path);
        files.setResponseType('arraybuffer');
        files.setRequestHeader(this.requestHeader);
        files.setWithCredentials(this.withCredentials);
        for (const key of ['priority', 'cache']) if (this[key] !== undefined) files[key] = this[key];  // three r18x
        const {wrapU, pyramid, channel} = this.options;
        const fail = (error, managerSaw) => {
            if (onError) onError(error);
            else console.error(error);
            if (!managerSaw) this.manager.itemError(name);
            this.manager.itemEnd(name);
        };
        this.manager.itemStart(name);
        files.load(url, (buffer) => {
            heightsFromBytes(new Uint8Array(buffer), {name, channel})
                .then((heights) => createReliefMap(this.renderer, heights, {wrapU, pyramid}))
                .then((map) => {
                    onLoad(map);
                    this.manager.itemEnd(name);
                }, (error) => fail(error, false));
        }, onProgress, (error) => fail(readError(name, error), true));  // the FileLoader told the manager
    }
}
