// The fuzzer's seed corpus (and any crash input added to it), replayed through the fuzz
// target's own entry point with the normal compiler: every file must load or be refused
// as the target demands (tests/fuzz/HeightMapFuzzTarget.cpp aborts otherwise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "TestSupport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

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
