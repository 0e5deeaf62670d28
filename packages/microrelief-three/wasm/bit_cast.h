// bit_cast.h: std::bit_cast for emscripten 3.1.6 (Debian 12), whose libc++ predates it
// (LLVM 14's libc++ has no <bit> bit_cast, clang 14 has the builtin behind it). Forced into
// every translation unit of the WebAssembly build (scripts/build.mjs: -include), so that
// src/core/heightmap/*.cpp compile unchanged; a newer libc++ defines __cpp_lib_bit_cast and
// this adds nothing.
#pragma once
#include <bit>
#ifndef __cpp_lib_bit_cast
namespace std {
template <class To, class From>
constexpr To bit_cast(const From& from) noexcept {
    return __builtin_bit_cast(To, from);
}
}  // namespace std
#endif
