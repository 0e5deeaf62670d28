// paged_map.glsl: how relief.frag reads a map larger than one texture, through pages
// (gl/PagedPyramid.h): the host side of the library's read hooks (texture_reads.glsl).
//
// The samples and the fine levels of the windows (max_pyramid.glsl) are cut into pages of
// 2^shift x 2^shift texels, held in one texture array (the pool, a page a layer) as far
// as a memory budget lets them; the coarse levels of the windows lie whole in one texture
// (its level 0 is the windows' level L, L the first level not paged). A page table says
// which pages are resident and where. A read of a texel whose page is absent records the
// page as wanted in the use buffer and stands in for the texel with the finest resident
// window above it:
//  * window (k, t) lies inside window (k + 1, min(t >> 1, last)) (its texels
//    [t 2^k, (t + 2) 2^k) inside [(t >> 1) 2^(k+1), ((t >> 1) + 2) 2^(k+1)), or the last
//    window of a row, which reaches to the map's edge), and a window is the max over what
//    it covers, so the coarser one is at least as high;
//  * sample p is one of the nine values window (0, p)'s texel square bound is the largest
//    of (pyramid_bound.glsl), rounded up for storage, so window (0, p) times 2^S is at
//    least the sample.
// So what a pass reads is never below what the full map holds: a bound stays a bound, and
// a leaf made of stood-in samples lies on or above the true surface (bilinear and
// biquadratic weights are >= 0). A pass that wanted nothing read every texel from its
// page: its picture is the full map's, bit for bit. The host draws again, after loading
// what was wanted, until a pass wants nothing (HeadlessRenderer).
//
// The page table is one uint buffer; where its parts lie is the host's (PagedPyramid.h,
// given here as defines): MICRORELIEF_PAGE_INFO_AT: L, S (two's complement), shift, the
// draw's stamp; MICRORELIEF_PAGE_LEVELS_AT: per page level l (0 the samples, 1 + k windows
// level k, up to windows level L, whose size only is used): its first entry, its width,
// its height, a spare word; MICRORELIEF_PAGE_ENTRIES_AT: an entry per page, 0 when absent,
// else its pool layer + 1.
//
// The use buffer has a word per page, in the entries' order: each read of a page writes
// the draw's stamp there (1 to 2^31 - 1, which the host changes each time it reads the
// buffer), with the top bit set where the page was absent and wanted. So the host learns
// every page a draw read, resident or not, and evicts the least recently used
// (PagedPyramid::load): the pages every ray reads stay resident. Within a draw the table
// does not change, so all of a page's writes in it store the same word: plain stores, no
// atomics, never a wrong value. The cost: a store a paged read (of the samples or of a
// paged window level, resident or not; the coarse texture's reads store nothing) and a
// read of the stamp, a word every invocation shares. One store in the code, not one a
// case: on llvmpipe, where every page a frame reads is resident, the paged frame took
// 4.0 times the whole textures' time with it as with the wants alone, but 4.75 times with
// a store for each case, and 4.5 with one store and a table word to switch the resident
// marks off (docs/perf/2026-12-07-paged-lru.md).
#ifndef MICRORELIEF_PAGED_MAP_GLSL
#define MICRORELIEF_PAGED_MAP_GLSL

#include "microrelief/precision.glsl"

#ifndef MICRORELIEF_PAGED
#define MICRORELIEF_PAGED 0
#endif
#if MICRORELIEF_PAGED

layout(std430, binding = 1) readonly buffer MicroreliefPageTable {
    uint mr_pageTable[];
};
layout(std430, binding = 2) writeonly buffer MicroreliefPageUse {
    uint mr_pageUse[];
};
uniform highp sampler2DArray mr_pagePool;  // the resident pages, R32F, a page a layer
uniform highp sampler2D mr_pageCoarse;     // windows level L and coarser, R16F, bound / 2^S

int mr_pagedLevels() {
    return int(mr_pageTable[MICRORELIEF_PAGE_INFO_AT]);
}

int mr_pageShift() {
    return int(mr_pageTable[MICRORELIEF_PAGE_INFO_AT + 2]);
}

ivec2 mr_pageLevelSize(int l) {
    int at = MICRORELIEF_PAGE_LEVELS_AT + 4 * l;
    return ivec2(int(mr_pageTable[at + 1]), int(mr_pageTable[at + 2]));
}

// The word this draw writes for a page it reads (see the top of this file).
uint mr_pageStamp() {
    return mr_pageTable[MICRORELIEF_PAGE_INFO_AT + 3];
}

// The entry of the page holding texel t of page level l (t inside the level). A resident
// page is marked read by this draw; an absent one is marked wanted when `want`, and left
// unmarked when not (a stand-in's finer pages: not read).
uint mr_pageEntry(int l, ivec2 t, bool want) {
    int at = MICRORELIEF_PAGE_LEVELS_AT + 4 * l;
    int shift = mr_pageShift();
    int across = (int(mr_pageTable[at + 1]) + (1 << shift) - 1) >> shift;
    ivec2 page = t >> shift;
    int index = int(mr_pageTable[at]) + page.y * across + page.x;
    uint entry = mr_pageTable[MICRORELIEF_PAGE_ENTRIES_AT + index];
    uint wanted = entry != 0u ? 0u : 0x80000000u;
    if (entry != 0u || want) mr_pageUse[index] = mr_pageStamp() | wanted;
    return entry;
}

float mr_poolTexel(uint entry, ivec2 t) {
    ivec2 inPage = t & ((1 << mr_pageShift()) - 1);
    return texelFetch(mr_pagePool, ivec3(inPage, int(entry) - 1), 0).r;
}

// Window (k, t) as stored (bound / 2^S), or where its page is absent the finest resident
// window above it (see the top of this file); only the page of (k, t) itself is wanted,
// and only when `want`.
float mr_pagedWindow(ivec2 t, int k, bool want) {
    int paged = mr_pagedLevels();
    for (; k < paged; ++k) {
        uint entry = mr_pageEntry(1 + k, t, want);
        if (entry != 0u) return mr_poolTexel(entry, t);
        want = false;
        t = min(t >> 1, mr_pageLevelSize(2 + k) - 1);
    }
    return texelFetch(mr_pageCoarse, t, k - paged).r;
}

// 2^S, built from its bits as mr_pyramidScale builds it.
float mr_pagedScale() {
    int s = int(mr_pageTable[MICRORELIEF_PAGE_INFO_AT + 1]);
    return uintBitsToFloat(uint(s + 127) << 23u);
}

// Sample t, or where its page is absent the bound above it (window (0, t) or coarser).
float mr_pagedSample(ivec2 t) {
    uint entry = mr_pageEntry(0, t, true);
    if (entry != 0u) return mr_poolTexel(entry, t);
    return mr_pagedWindow(t, 0, false) * mr_pagedScale();
}

// The library's reads (texture_reads.glsl) through the pages: single reads of samples
// (a gather's four may lie on two to four pages), and the windows by level.
#define MICRORELIEF_TEXTURE_GATHER 0
#define MICRORELIEF_READ_SAMPLE(heights, texel) mr_pagedSample(texel)
#define MICRORELIEF_READ_PYRAMID(pyramid, texel, level, levelSize) mr_pagedWindow(texel, level, true)

#endif
#endif
