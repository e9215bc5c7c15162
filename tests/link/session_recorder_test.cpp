#include "link/session_recorder.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "link/session_reader.hpp"

namespace kapfix::link {
namespace {

class LinkSessionRecordTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "kapfix_record_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    folder_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  std::string File() const { return (folder_ / "session.kfx").string(); }

  std::filesystem::path folder_;
};

TEST_F(LinkSessionRecordTest, ReaderGetsBackWhatTheRecorderWrote) {
  const std::string binary("\x00\x01\xff payload", 11);
  {
    SessionRecorder recorder(File());
    recorder.Write("telemetry", binary, 42);
    recorder.Write("log", "", -1);
    EXPECT_EQ(recorder.messages(), 2U);
  }
  SessionReader reader(File());
  const auto first = reader.Next();
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->topic, "telemetry");
  EXPECT_EQ(first->payload, binary);
  EXPECT_EQ(first->receive_time_us, 42);
  const auto second = reader.Next();
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->topic, "log");
  EXPECT_EQ(second->receive_time_us, -1);
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_TRUE(reader.error().empty());
}

TEST_F(LinkSessionRecordTest, ReaderRefusesAFileWithoutTheMagic) {
  std::ofstream(File()) << "not a recording";
  EXPECT_THROW(SessionReader reader(File()), std::runtime_error);
}

TEST_F(LinkSessionRecordTest, CutRecordingKeepsItsCompleteMessagesAndSaysItWasCut) {
  {
    SessionRecorder recorder(File());
    recorder.Write("telemetry", "one", 1);
    recorder.Write("telemetry", "two", 2);
  }
  std::filesystem::resize_file(File(), std::filesystem::file_size(File()) - 2);
  SessionReader reader(File());
  EXPECT_TRUE(reader.Next().has_value());
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_FALSE(reader.error().empty());
}

}  // namespace
}  // namespace kapfix::link
