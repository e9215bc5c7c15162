// SessionReader: the length-delimited session file, the old KFXREC01 recordings it still
// replays, and files it refuses or reads only up to a cut, with a reason naming the offset.
#include "link/session_reader.hpp"

#include <gmock/gmock.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "kapfix/v1/session.pb.h"
#include "link/session_recorder.hpp"

namespace kapfix::link {
namespace {

using ::testing::HasSubstr;

class LinkSessionReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "kapfix_reader_XXXXXX").string();
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    folder_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  std::string File(const std::string& name = "session.kfx") const {
    return (folder_ / name).string();
  }
  // The reason SessionReader's constructor gives for refusing `path`, or "" if it accepts.
  static std::string Refusal(const std::string& path) {
    try {
      SessionReader reader(path);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "";
  }

  std::filesystem::path folder_;
};

// The old framing, written here byte by byte as the format describes it (little-endian).
void PutLittleEndian(std::ofstream& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.put(static_cast<char>((value >> (8 * i)) & 0xFFU));
}
void PutLegacyMessage(std::ofstream& out, std::uint64_t time_us, const std::string& topic,
                      const std::string& payload) {
  PutLittleEndian(out, time_us, 8);
  PutLittleEndian(out, topic.size(), 4);
  out << topic;
  PutLittleEndian(out, payload.size(), 4);
  out << payload;
}

TEST_F(LinkSessionReaderTest, OldKfxrec01RecordingStillReplays) {
  {
    std::ofstream out(File(), std::ios::binary);
    out << "KFXREC01";
    PutLegacyMessage(out, 42, "telemetry", std::string("\x00\x01", 2));
    PutLegacyMessage(out, 43, "log", "line");
  }
  SessionReader reader(File());
  EXPECT_EQ(reader.format(), "KFXREC01");
  const auto first = reader.Next();
  ASSERT_TRUE(first.has_value()) << reader.error();
  EXPECT_EQ(first->receive_time_us, 42);
  EXPECT_EQ(first->topic, "telemetry");
  EXPECT_EQ(first->payload, std::string("\x00\x01", 2));
  const auto second = reader.Next();
  ASSERT_TRUE(second.has_value()) << reader.error();
  EXPECT_EQ(second->topic, "log");
  EXPECT_EQ(second->payload, "line");
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_TRUE(reader.error().empty()) << reader.error();
}

TEST_F(LinkSessionReaderTest, CutOldRecordingKeepsItsCompleteMessagesAndNamesTheOffset) {
  {
    std::ofstream out(File(), std::ios::binary);
    out << "KFXREC01";
    PutLegacyMessage(out, 1, "telemetry", "one");  // 8 + 4 + 9 + 4 + 3 = 28 bytes, at 8
    PutLegacyMessage(out, 2, "telemetry", "two");  // at 36
  }
  std::filesystem::resize_file(File(), std::filesystem::file_size(File()) - 2);
  SessionReader reader(File());
  EXPECT_TRUE(reader.Next().has_value());
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_THAT(reader.error(), HasSubstr("at byte 36"));
}

TEST_F(LinkSessionReaderTest, CutRecordingKeepsItsCompleteMessagesAndNamesTheOffset) {
  // Where the second record starts: the size of the same recording holding only the first.
  {
    SessionRecorder recorder(File("one.kfx"));
    recorder.Write("telemetry", "one", 1);
  }
  {
    SessionRecorder recorder(File());
    recorder.Write("telemetry", "one", 1);
    recorder.Write("telemetry", "two", 2);
  }
  std::filesystem::resize_file(File(), std::filesystem::file_size(File()) - 2);
  SessionReader reader(File());
  const auto first = reader.Next();
  ASSERT_TRUE(first.has_value()) << reader.error();
  EXPECT_EQ(first->payload, "one");
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_THAT(reader.error(),
              HasSubstr("cut short or corrupted in the record at byte " +
                        std::to_string(std::filesystem::file_size(File("one.kfx")))));
  EXPECT_FALSE(reader.Next().has_value());  // and stays at the cut
}

TEST_F(LinkSessionReaderTest, CorruptedLengthEndsTheReadingWithAReasonNotACrash) {
  {
    SessionRecorder recorder(File());
    recorder.Write("telemetry", "one", 1);
  }
  {
    // A varint claiming about 4 GiB, then a few bytes: neither a record nor the end.
    std::ofstream out(File(), std::ios::binary | std::ios::app);
    out << std::string("\xff\xff\xff\xff\x0f garbage", 13);
  }
  SessionReader reader(File());
  EXPECT_TRUE(reader.Next().has_value());
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_THAT(reader.error(), HasSubstr("cut short or corrupted"));
}

TEST_F(LinkSessionReaderTest, RefusesAFileInNeitherFormatNamingBoth) {
  std::ofstream(File()) << "not a recording";
  const std::string reason = Refusal(File());
  EXPECT_THAT(reason, HasSubstr("is not a kapfix session recording"));
  EXPECT_THAT(reason, HasSubstr("kapfix-session"));
  EXPECT_THAT(reason, HasSubstr("KFXREC01"));
}

TEST_F(LinkSessionReaderTest, RefusesAnEmptyFile) {
  std::ofstream{File()};
  EXPECT_THAT(Refusal(File()), HasSubstr("is not a kapfix session recording"));
}

TEST_F(LinkSessionReaderTest, RefusesANewerVersionNamingIt) {
  {
    kapfix::v1::SessionRecord record;
    record.mutable_format()->set_name("kapfix-session");
    record.mutable_format()->set_version(2);
    std::ofstream out(File(), std::ios::binary);
    ASSERT_TRUE(google::protobuf::util::SerializeDelimitedToOstream(record, &out));
  }
  EXPECT_THAT(Refusal(File()), HasSubstr("of version 2; this build reads version 1"));
}

TEST_F(LinkSessionReaderTest, RefusesAMissingFileNamingIt) {
  EXPECT_THAT(Refusal(File("absent.kfx")), HasSubstr("cannot open '" + File("absent.kfx")));
}

}  // namespace
}  // namespace kapfix::link
