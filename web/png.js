// png.js: PNG files decoded in the page, to the samples the C++ loader reads.
//
// A browser decodes images through <img>, a canvas or createImageBitmap to 8 bits a
// channel, colour-managed: a 16-bit height map would lose its low byte and the relief
// would differ from microrelief-render's. So the file is decoded here, as libpng does
// for OpenImageIO: the chunks checked first (as src/io/PngCheck.cpp does: lengths
// within the file, CRCs, IHDR first and valid, the size from IHDR within the limit before
// anything is allocated, PLTE where a palette needs it, IDAT contiguous, IEND), the image
// data inflated (the browser's DecompressionStream, zlib) to exactly the size IHDR
// implies, every row's filter undone. Interlaced (Adam7) files are refused.
//
// Heights follow src/io/HeightMapFile.cpp, which reads through OpenImageIO 2.4
// (Debian 12): channel 0, integer samples normalised by their type's range as OpenImageIO
// does it, in float: v * float(1 / 255) or v * float(1 / 65535) (a product, not a
// quotient: 167 of the bundled map's 65536 samples differ between the two). Before that,
// as libpng and OpenImageIO hand the samples over: grey of 1, 2 or 4 bits expanded to 8
// (x 255, 85, 17), a palette index to its colour, a tRNS chunk made an alpha channel, and
// the colour multiplied by the alpha ("associated"): (v a) / max in integers, or where a
// gAMA chunk (and no sRGB chunk) gives a gamma g other than 1, trunc(v (a / max)^g) with
// g = 1 / gAMA rounded to hundredths. Measured against OpenImageIO: every 8-bit value and
// alpha pair, 65536 16-bit pairs, gammas 1, 1.8 and 2.2, tRNS on grey, RGB and palettes.

// The largest side a height map may have (README, Reliability: the programs' limit).
export const kMaxMapSide = 16384;

const kSignature = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

// A refusal: one line, naming what is wrong (the caller prefixes the file's name).
export class PngError extends Error {}

const crcTable = (() => {
    const table = new Uint32Array(256);
    for (let n = 0; n < 256; ++n) {
        let c = n;
        for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
        table[n] = c >>> 0;
    }
    return table;
})();

function crc32(bytes, start, end) {
    let c = 0xffffffff;
    for (let k = start; k < end; ++k) c = crcTable[(c ^ bytes[k]) & 0xff] ^ (c >>> 8);
    return (c ^ 0xffffffff) >>> 0;
}

function bigEndian(bytes, at) {
    return ((bytes[at] << 24) | (bytes[at + 1] << 16) | (bytes[at + 2] << 8) | bytes[at + 3]) >>> 0;
}

function chunkName(bytes, at) {
    let name = '';
    for (let k = 0; k < 4; ++k) {
        const c = bytes[at + k];
        name += c >= 0x20 && c < 0x7f ? String.fromCharCode(c) : '?';
    }
    return name;
}

// Channels of a colour type (0: invalid) and the bit depths it allows.
const kChannels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4};
function validDepth(colorType, depth) {
    if (colorType === 0) return [1, 2, 4, 8, 16].includes(depth);
    if (colorType === 3) return [1, 2, 4, 8].includes(depth);
    return depth === 8 || depth === 16;
}

// IHDR's fields, checked as libpng's png_check_IHDR does, then against the size limit.
function readHeader(bytes) {
    if (bytes.length < 8 + 8 + 13 + 4) throw new PngError('the file ends inside the PNG header');
    if (bigEndian(bytes, 8) !== 13 || chunkName(bytes, 12) !== 'IHDR')
        throw new PngError('the first chunk is not a 13-byte IHDR');
    const h = {
        width: bigEndian(bytes, 16),
        height: bigEndian(bytes, 20),
        bitDepth: bytes[24],
        colorType: bytes[25],
        interlaced: bytes[28] === 1,
    };
    if (h.width === 0 || h.height === 0) throw new PngError('IHDR gives a zero size');
    if (!(h.colorType in kChannels)) throw new PngError(`IHDR colour type ${h.colorType}`);
    if (!validDepth(h.colorType, h.bitDepth))
        throw new PngError(`IHDR bit depth ${h.bitDepth} for colour type ${h.colorType}`);
    if (bytes[26] !== 0) throw new PngError(`IHDR compression method ${bytes[26]}`);
    if (bytes[27] !== 0) throw new PngError(`IHDR filter method ${bytes[27]}`);
    if (bytes[28] > 1) throw new PngError(`IHDR interlace method ${bytes[28]}`);
    if (h.width > kMaxMapSide || h.height > kMaxMapSide)
        throw new PngError(`${h.width} x ${h.height} is larger than the ${kMaxMapSide} x ${kMaxMapSide} a map may have`);
    if (h.interlaced)
        throw new PngError('an interlaced (Adam7) PNG, which this page does not decode: save it non-interlaced');
    h.channels = kChannels[h.colorType];
    return h;
}

// The chunks after the signature: lengths within the file, every CRC, the order PNG asks
// for. Returns the header, the palette (or null) and the IDAT payloads in order.
function readChunks(bytes) {
    for (let k = 0; k < 8; ++k) {
        if (bytes[k] !== kSignature[k]) throw new PngError('not a PNG file (no PNG signature)');
    }
    const header = readHeader(bytes);
    let palette = null, transparency = null, gamma = null, srgb = false;
    let seenData = false, dataDone = false, at = 8;
    const data = [];
    for (;;) {
        if (at + 12 > bytes.length) throw new PngError('the file ends before IEND (truncated)');
        const length = bigEndian(bytes, at);
        const name = chunkName(bytes, at + 4);
        if (length > 0x7fffffff || at + 12 + length > bytes.length)
            throw new PngError(`chunk ${name}: its length runs past the end of the file (truncated)`);
        const crc = bigEndian(bytes, at + 8 + length);
        if (crc32(bytes, at + 4, at + 8 + length) !== crc) throw new PngError(`chunk ${name}: bad CRC`);
        const body = bytes.subarray(at + 8, at + 8 + length);
        const critical = !(bytes[at + 4] & 0x20);  // the first letter's case: upper is critical
        at += 12 + length;
        if (name === 'IHDR') {
            if (at !== 8 + 25) throw new PngError('a second IHDR chunk');
            continue;
        }
        if (name === 'IDAT') {
            if (dataDone) throw new PngError('IDAT chunks are not contiguous');
            if (header.colorType === 3 && !palette) throw new PngError('a palette image without PLTE before IDAT');
            seenData = true;
            data.push(body);
            continue;
        }
        if (seenData) dataDone = true;
        if (name === 'PLTE') {
            if (seenData) throw new PngError('PLTE after IDAT');
            if (length % 3 !== 0 || length === 0 || length > 768) throw new PngError(`PLTE of ${length} bytes`);
            palette = body;
        } else if (name === 'tRNS' && !seenData) {
            transparency = body;
        } else if (name === 'gAMA' && !seenData && length === 4) {
            gamma = bigEndian(body, 0);
        } else if (name === 'sRGB' && !seenData) {
            srgb = true;
        } else if (name === 'IEND') {
            if (!seenData) throw new PngError('no IDAT chunk (no image data)');
            return {header, palette, data, transparency: validTransparency(header, palette, transparency),
                    gamma: srgb ? null : pngGamma(gamma)};
        } else if (critical) {
            throw new PngError(`unknown critical chunk ${name}`);
        }
    }
}

// tRNS as libpng takes it: grey's or RGB's key of the right length, a palette's alphas
// (no more than its colours); otherwise ignored (libpng's benign error, a warning).
function validTransparency(header, palette, body) {
    if (!body) return null;
    if (header.colorType === 0 && body.length === 2) return {key: [bigEndian16(body, 0)]};
    if (header.colorType === 2 && body.length === 6)
        return {key: [bigEndian16(body, 0), bigEndian16(body, 2), bigEndian16(body, 4)]};
    if (header.colorType === 3 && palette && body.length > 0 && body.length <= palette.length / 3)
        return {alphas: body};
    return null;
}

const bigEndian16 = (bytes, at) => (bytes[at] << 8) | bytes[at + 1];

// OpenImageIO's "oiio:Gamma" from gAMA: 1 / (gAMA / 100000), rounded to hundredths in
// float; null where there is none (or it is 1: then alpha is associated in integers).
function pngGamma(gAMA) {
    if (!gAMA) return null;
    const f = Math.fround;
    const g = f(Math.round(f(100 * f(1 / (gAMA * 0.00001)))) / 100);
    return g === 1 ? null : g;
}

// The zlib stream of the IDAT chunks inflated to exactly `expected` bytes. What follows
// them in the stream is ignored, as libpng ignores it; fewer bytes are refused.
async function inflate(parts, expected) {
    if (typeof DecompressionStream === 'undefined')
        throw new PngError('this browser has no DecompressionStream to inflate PNG data');
    const stream = new DecompressionStream('deflate');
    const writer = stream.writable.getWriter();
    (async () => {
        try {
            for (const part of parts) await writer.write(part);
            await writer.close();
        } catch (e) {
            // The reader reports it.
        }
    })();
    const reader = stream.readable.getReader();
    const out = new Uint8Array(expected);
    let at = 0;
    try {
        for (;;) {
            const {value, done} = await reader.read();
            if (done) break;
            const take = Math.min(value.length, expected - at);
            out.set(value.subarray(0, take), at);
            at += take;
            if (at === expected) {
                reader.cancel().catch(() => {});
                break;
            }
        }
    } catch (e) {
        if (at !== expected) throw new PngError(`IDAT: truncated or corrupt image data (${e.message})`);
    }
    if (at !== expected)
        throw new PngError(`IDAT: not enough image data (${at} of the ${expected} bytes IHDR implies)`);
    return out;
}

function paeth(a, b, c) {
    const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// Undoes each row's filter in place; returns the rows' bytes without filter bytes.
function unfilter(raw, header) {
    const bitsPerPixel = header.channels * header.bitDepth;
    const rowBytes = Math.ceil((header.width * bitsPerPixel) / 8);
    const bpp = Math.max(1, bitsPerPixel >> 3);
    const rows = new Uint8Array(rowBytes * header.height);
    for (let y = 0; y < header.height; ++y) {
        const filter = raw[y * (rowBytes + 1)];
        if (filter > 4) throw new PngError(`IDAT: bad filter type ${filter} in row ${y}`);
        const src = y * (rowBytes + 1) + 1, dst = y * rowBytes, up = dst - rowBytes;
        for (let x = 0; x < rowBytes; ++x) {
            const a = x >= bpp ? rows[dst + x - bpp] : 0;
            const b = y > 0 ? rows[up + x] : 0;
            const c = y > 0 && x >= bpp ? rows[up + x - bpp] : 0;
            let v = raw[src + x];
            if (filter === 1) v += a;
            else if (filter === 2) v += b;
            else if (filter === 3) v += (a + b) >> 1;
            else if (filter === 4) v += paeth(a, b, c);
            rows[dst + x] = v & 0xff;
        }
    }
    return {rows, rowBytes};
}

// Decodes `bytes` (a Uint8Array of a whole file): {width, height, channels, bitDepth,
// values}, values the samples as OpenImageIO reads them (see the top of this file: grey
// of fewer bits expanded to 8, a palette to RGB, tRNS to alpha, colour associated with
// alpha), `channels` a pixel, row 0 first; bitDepth 8 or 16. Throws PngError with the reason.
export async function decodePng(bytes) {
    const {header, palette, data, transparency, gamma} = readChunks(bytes);
    const bitsPerPixel = header.channels * header.bitDepth;
    const expected = (Math.ceil((header.width * bitsPerPixel) / 8) + 1) * header.height;
    const raw = await inflate(data, expected);
    const {rows, rowBytes} = unfilter(raw, header);
    const {width, height, bitDepth, colorType} = header;
    const deep = bitDepth === 16;
    const max = deep ? 65535 : 255;
    // The samples as stored, one a channel (a palette's index, grey of 1 to 4 bits unscaled).
    const stored = (y, k) => {
        if (deep) return (rows[y * rowBytes + 2 * k] << 8) | rows[y * rowBytes + 2 * k + 1];
        if (bitDepth === 8) return rows[y * rowBytes + k];
        const bit = k * bitDepth;
        return (rows[y * rowBytes + (bit >> 3)] >> (8 - bitDepth - (bit & 7))) & ((1 << bitDepth) - 1);
    };
    const colours = colorType === 3 ? 3 : colorType === 4 ? 1 : colorType === 6 ? 3 : header.channels;
    const hasAlpha = colorType === 4 || colorType === 6 || transparency !== null;
    const channels = colours + (hasAlpha ? 1 : 0);
    const values = deep ? new Uint16Array(width * height * channels) : new Uint8Array(width * height * channels);
    const greyScale = colorType === 0 ? [0, 255, 85, 0, 17, 0, 0, 0, 1][bitDepth] || 1 : 1;
    const pixel = new Array(4);
    for (let y = 0; y < height; ++y) {
        for (let x = 0; x < width; ++x) {
            const out = (y * width + x) * channels;
            let alpha = max;
            if (colorType === 3) {
                const index = stored(y, x);
                if (3 * index + 2 >= palette.length)
                    throw new PngError(`palette index ${index} beyond the PLTE's ${palette.length / 3} colours`);
                for (let c = 0; c < 3; ++c) pixel[c] = palette[3 * index + c];
                if (transparency) alpha = index < transparency.alphas.length ? transparency.alphas[index] : 255;
            } else {
                for (let c = 0; c < header.channels; ++c) pixel[c] = stored(y, x * header.channels + c);
                if (colorType === 4 || colorType === 6) alpha = pixel[colours];
                else if (transparency && transparency.key.every((key, c) => key === pixel[c])) alpha = 0;
                for (let c = 0; c < colours; ++c) pixel[c] *= greyScale;
            }
            for (let c = 0; c < colours; ++c) values[out + c] = associate(pixel[c], alpha, max, gamma);
            if (hasAlpha) values[out + colours] = alpha;
        }
    }
    return {width, height, channels, bitDepth: deep ? 16 : 8, values};
}

// A colour sample multiplied by its alpha as OpenImageIO 2.4's PNG reader does it.
function associate(value, alpha, max, gamma) {
    if (alpha === max) return value;
    if (gamma === null) return Math.floor((value * alpha) / max);
    const f = Math.fround;
    return Math.trunc(f(value * f(Math.pow(f(alpha * f(1 / max)), gamma))));
}

// The heights of channel `channel` (0 by default), as loadHeightMap reads them.
export function heightsFromPng(png, channel = 0) {
    if (channel < 0 || channel >= png.channels)
        throw new PngError(`channel ${channel} is out of range; the image has ${png.channels} channel(s)`);
    const scale = Math.fround(1 / (png.bitDepth === 16 ? 65535 : 255));
    const count = png.width * png.height;
    const heights = new Float32Array(count);
    for (let k = 0; k < count; ++k) heights[k] = png.values[k * png.channels + channel] * scale;
    return heights;
}
