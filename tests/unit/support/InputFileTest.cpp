#include "support/InputFile.h"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace cbtl::support {
namespace {

class InputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("cbtl-input-" + std::to_string(::getpid()) + "-" +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // The error readInputFile throws for `path`, or a failure when it reads it.
  static InputFileError refusal(const std::string& path, std::uintmax_t limit) {
    try {
      readInputFile(path, limit, "profile");
    } catch (const InputFileError& e) {
      return e;
    }
    ADD_FAILURE() << path << " was read";
    return InputFileError(InputFileError::Kind::CannotOpen, path, "read");
  }

  std::filesystem::path dir_;
};

TEST_F(InputFileTest, ARegularFileIsReadWhole) {
  const std::string path = (dir_ / "p.json").string();
  std::ofstream(path, std::ios::binary) << std::string("{\"a\": 1}\0tail", 13);
  EXPECT_EQ(readInputFile(path, 13, "profile"), std::string("{\"a\": 1}\0tail", 13));
  EXPECT_EQ(readInputFile(path, kMaxDataBytes, "profile").size(), 13u);
}

TEST_F(InputFileTest, AFileOverTheLimitIsRefusedWithTheLimit) {
  const std::string path = (dir_ / "p.json").string();
  std::ofstream(path) << std::string(1025, 'x');
  const InputFileError e = refusal(path, 1024);
  EXPECT_EQ(e.kind, InputFileError::Kind::TooLarge);
  EXPECT_EQ(std::string(e.what()), path + ": the profile is larger than 1 KiB, the most cbtl reads as one");
  // A sparse file of 300 MiB is refused from its size, without reading it.
  const std::string sparse = (dir_ / "sparse.json").string();
  std::ofstream(sparse).close();
  std::filesystem::resize_file(sparse, 300 * kMiB);
  EXPECT_EQ(refusal(sparse, kMaxDataBytes).kind, InputFileError::Kind::TooLarge);
  EXPECT_EQ(describeBytes(kMaxDataBytes), "256 MiB");
  EXPECT_EQ(describeBytes(1000), "1000 bytes");
}

TEST_F(InputFileTest, WhatIsNotARegularFileIsRefusedWithoutBlocking) {
  const std::string fifo = (dir_ / "pipe").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const InputFileError pipe = refusal(fifo, kMaxDataBytes);  // no writer: opening it blocking would never return
  EXPECT_EQ(pipe.kind, InputFileError::Kind::NotRegular);
  EXPECT_EQ(pipe.reason, "not a regular file (a pipe), so not read as the profile");
  EXPECT_EQ(refusal("/dev/zero", kMaxDataBytes).reason, "not a regular file (a device), so not read as the profile");
  EXPECT_EQ(refusal(dir_.string(), kMaxDataBytes).kind, InputFileError::Kind::NotRegular);
  const InputFileError missing = refusal((dir_ / "none.json").string(), kMaxDataBytes);
  EXPECT_EQ(missing.kind, InputFileError::Kind::CannotOpen);
  EXPECT_EQ(missing.reason, "cannot read the profile (No such file or directory)");
}

}  // namespace
}  // namespace cbtl::support
