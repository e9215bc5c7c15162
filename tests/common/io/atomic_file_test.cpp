#include "common/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace kapfix {
namespace {

std::filesystem::path FreshDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   (name + "_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(AtomicFileTest, WritesTheBytesAndLeavesNoTemporary) {
  const auto dir = FreshDir("kapfix_atomic_ok");
  WriteFileAtomically(dir / "a.txt", "hello");
  std::ifstream in(dir / "a.txt");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "hello");
  EXPECT_FALSE(std::filesystem::exists(dir / "a.txt.part"));
  std::filesystem::remove_all(dir);
}

TEST(AtomicFileTest, AFailedWriteNamesTheFileAndLeavesNothing) {
  const auto dir = FreshDir("kapfix_atomic_fail");
  const auto target = dir / "missing_folder" / "b.txt";
  try {
    WriteFileAtomically(target, "x");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("b.txt"), std::string::npos);
  }
  EXPECT_FALSE(std::filesystem::exists(target));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kapfix
