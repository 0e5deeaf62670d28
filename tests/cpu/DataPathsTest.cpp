// Where the library finds its data folder (core/DataPaths.h): MICRORELIEF_DATA_DIR, else the
// folder a program named (setDataDirectory), else beside the running program.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include <unistd.h>

#include "microrelief/core/DataPaths.h"
#include "microrelief/core/Error.h"

using namespace microrelief;

namespace {

// MICRORELIEF_DATA_DIR unset for the test's life, then as it was; the folder a program
// named reset either way.
class DataFolder : public ::testing::Test {
protected:
    void SetUp() override {
        if (const char* value = std::getenv("MICRORELIEF_DATA_DIR")) saved_ = value;
        unsetenv("MICRORELIEF_DATA_DIR");
        scratch_ = std::filesystem::temp_directory_path() /
                   ("microrelief-data-" + std::to_string(::getpid()));
        std::filesystem::create_directories(scratch_ / "shaders");
    }
    void TearDown() override {
        setDataDirectory({});
        if (saved_) setenv("MICRORELIEF_DATA_DIR", saved_->c_str(), 1);
        std::filesystem::remove_all(scratch_);
    }
    std::optional<std::string> saved_;
    std::filesystem::path scratch_;
};

}  // namespace

TEST_F(DataFolder, AFolderTheProgramNamesIsUsedAndTheVariableStillWins) {
    const std::filesystem::path beside = dataDirectory();  // the test's own build tree
    setDataDirectory(scratch_);
    EXPECT_EQ(dataDirectory(), scratch_);
    EXPECT_EQ(shaderDirectory(), scratch_ / "shaders");
    EXPECT_EQ(defaultHeightMapPath(), scratch_ / "assets" / "cobbles.png");
    setenv("MICRORELIEF_DATA_DIR", beside.c_str(), 1);
    EXPECT_EQ(dataDirectory(), beside);
    unsetenv("MICRORELIEF_DATA_DIR");
    setDataDirectory({});
    EXPECT_EQ(dataDirectory(), beside);
}

TEST_F(DataFolder, AFolderWithoutShadersIsRefusedAndNothingChanges) {
    const std::filesystem::path beside = dataDirectory();
    const std::filesystem::path empty = scratch_ / "shaders";  // holds no shaders/ itself
    try {
        setDataDirectory(empty);
        ADD_FAILURE() << "a folder without shaders/ was taken";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_EQ(std::string(e.what()),
                  empty.string() +
                      ": not the library's data folder (it holds no shaders/; an install's "
                      "share/microrelief does)");
    }
    EXPECT_EQ(dataDirectory(), beside);
}
