// The fuzzer's seed corpus (and any crash input added to it), replayed through the fuzz
// target's own entry point with the normal compiler: every file must load or be refused
// as the target demands (tests/fuzz/HeightMapFuzzTarget.cpp aborts otherwise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <vector>

#include "TestSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

// libFuzzer's -malloc_limit_mb=512 (scripts/fuzz.sh) for the replay: the global operator
// new, which OpenImageIO and OpenEXR call too, aborts on one allocation of more than 512
// MiB. Inputs load maps of at most 2048 x 2048 (16 MiB of samples), so such a request is
// a header's lie believed somewhere in the loading path.
namespace {
constexpr std::size_t kAllocationLimit = std::size_t{512} << 20;

void* allocate(std::size_t size) {
    if (size > kAllocationLimit) {
        std::fprintf(stderr, "fuzz replay: an allocation of %zu bytes\n", size);
        std::abort();
    }
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) {
    return allocate(size);
}
void* operator new[](std::size_t size) {
    return allocate(size);
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}

namespace {

const std::filesystem::path kCorpus = MICRORELIEF_FUZZ_CORPUS_DIR;

TEST(FuzzCorpus, EveryInputLoadsOrIsRefusedWithOneNamedLine) {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(kCorpus))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    // The seeds: valid PNG, OpenEXR and TIFF maps and truncated and damaged ones.
    ASSERT_GE(files.size(), 10u) << kCorpus;
    for (const auto& file : files) {
        // The target aborts on a broken promise: name the input first.
        std::printf("replaying %s\n", file.filename().c_str());
        std::fflush(stdout);
        const std::vector<std::uint8_t> bytes = microrelief::test::readBytes(file);
        EXPECT_EQ(LLVMFuzzerTestOneInput(bytes.data(), bytes.size()), 0);
    }
}

}  // namespace
