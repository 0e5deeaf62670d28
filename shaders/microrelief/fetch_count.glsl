// fetch_count.glsl: counting the texture reads of a trace, for the instrumented variant that
// the benchmark and the tests use (the host defines MICRORELIEF_COUNT_FETCHES). Every read
// of the library says MICRORELIEF_FETCHED(n) with the number of texture instructions it
// makes; with the macro defined they add up in mr_fetchCount, this invocation's count
// (every trace of the invocation, shadow rays included), and without it the statement
// compiles to nothing, so no counter is threaded through the library's functions.
#ifndef MICRORELIEF_FETCH_COUNT_GLSL
#define MICRORELIEF_FETCH_COUNT_GLSL

#include "precision.glsl"

#ifdef MICRORELIEF_COUNT_FETCHES
int mr_fetchCount = 0;
#define MICRORELIEF_FETCHED(n) mr_fetchCount += (n)
#else
#define MICRORELIEF_FETCHED(n)
#endif

#endif
