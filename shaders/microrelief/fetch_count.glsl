// fetch_count.glsl: counting the texture reads of a trace, for the instrumented variant that
// the benchmark and the tests use (the host defines MICRORELIEF_COUNT_FETCHES). Every read
// of the library says MICRORELIEF_FETCHED(n) with the number of texture instructions it
// makes; with the macro defined they add up in mr_fetchCount, this invocation's count
// (every trace of the invocation, shadow rays included), and without it the statement
// compiles to nothing, so no counter is threaded through the library's functions. A read
// of a traversal's bounds (a max pyramid's texel, a cone map's) says
// MICRORELIEF_FETCHED_BOUNDS(n) instead: it counts in mr_fetchCount and in
// mr_boundFetchCount too, so that the reads of the samples (the last level, the surface)
// are the difference.
#ifndef MICRORELIEF_FETCH_COUNT_GLSL
#define MICRORELIEF_FETCH_COUNT_GLSL

#include "precision.glsl"

#ifdef MICRORELIEF_COUNT_FETCHES
int mr_fetchCount = 0;
int mr_boundFetchCount = 0;
#define MICRORELIEF_FETCHED(n) mr_fetchCount += (n)
#define MICRORELIEF_FETCHED_BOUNDS(n) mr_fetchCount += (n), mr_boundFetchCount += (n)
#else
#define MICRORELIEF_FETCHED(n)
#define MICRORELIEF_FETCHED_BOUNDS(n)
#endif

#endif
