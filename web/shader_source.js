// shader_source.js: GLSL sources assembled in the page from the files of shaders/, as
// src/gl/ShaderSource.cpp assembles them for the C++ renderer: `#version` and the
// feature `#define`s first, each `#include "..."` resolved against the including file's
// folder, then against the search folders in order, each file spliced once, and every
// splice marked `#line <index * 100000 + line> <index>` so that a compiler message names
// the real file and line (mapCompilerLog). The files are fetched from the server the page
// comes from: the shaders are the library's own, never a copy.

const kMaxIncludeDepth = 32;
const kLineStride = 100000;  // line numbers per file in the assembled source
const kInclude = /^\s*#\s*include\s+"([^"]+)"\s*$/;

// `url` made absolute against `base` and normalised (".." and "." removed).
function resolveUrl(name, base) {
    return new URL(name, base).href;
}

export class ShaderSource {
    constructor(version) {
        this.version = version;
        this.text = `#version ${version}\n`;
        this.files = [];  // source-string number -> file URL
    }
}

// Fetches each file once per page (a cache of texts by URL).
export class ShaderFiles {
    constructor() {
        this.texts = new Map();
    }

    // The text of `url`, or null when the server has no such file.
    async read(url) {
        if (!this.texts.has(url)) {
            this.texts.set(url, (async () => {
                const response = await fetch(url, {cache: 'no-store'});
                if (response.status === 404) return null;
                if (!response.ok) throw new Error(`${url}: cannot read the shader source (HTTP ${response.status})`);
                return response.text();
            })());
        }
        return this.texts.get(url);
    }

    // `file` (a URL) assembled for `version` with `defines` ([name, value] pairs) and the
    // search folders `includeDirs` (URLs ending in '/').
    async assemble(file, version, defines = [], includeDirs = []) {
        const source = new ShaderSource(version);
        for (const [name, value] of defines) source.text += `#define ${name}${value === '' ? '' : ' ' + value}\n`;
        await this.splice(source, resolveUrl(file, document.baseURI), includeDirs, 0);
        return source;
    }

    async splice(source, file, includeDirs, depth) {
        if (depth > kMaxIncludeDepth) throw new Error(`${file}: #include nested too deeply (a cycle?)`);
        const text = await this.read(file);
        if (text === null) throw new Error(`${file}: cannot open shader source`);
        const index = source.files.length;
        source.files.push(file);
        const marker = (line) => `#line ${index * kLineStride + line} ${index}\n`;
        source.text += marker(1);
        const lines = text.split('\n');
        if (lines.length > 0 && lines[lines.length - 1] === '') lines.pop();
        for (let number = 1; number <= lines.length; ++number) {
            let line = lines[number - 1];
            if (line.endsWith('\r')) line = line.slice(0, -1);
            const match = kInclude.exec(line);
            if (!match) {
                source.text += line + '\n';
                continue;
            }
            const target = await this.resolve(file, match[1], includeDirs);
            if (target === null) throw new Error(`${file}:${number}: #include "${match[1]}" not found`);
            // Each file once, as its include guard would have it anyway.
            if (!source.files.includes(target)) await this.splice(source, target, includeDirs, depth + 1);
            source.text += marker(number + 1);
        }
    }

    // The including file's folder first, then the search folders, in order.
    async resolve(from, name, includeDirs) {
        for (const base of [from, ...includeDirs]) {
            const candidate = resolveUrl(name, base);
            if ((await this.read(candidate)) !== null) return candidate;
        }
        return null;
    }
}

// A compiler log with "<index>:<line>" (ANGLE: "ERROR: 0:100123: ...") rewritten as
// "<file>:<line>", the file's path from the page's server root.
export function mapCompilerLog(log, files) {
    return log.replace(/(\d+):(\d+)/g, (whole, indexText, lineText) => {
        let index = Number(indexText), line = Number(lineText);
        if (line >= kLineStride) {
            index = Math.floor(line / kLineStride);
            line %= kLineStride;
        }
        if (index >= files.length) return whole;
        return `${new URL(files[index]).pathname}:${line}`;
    });
}
