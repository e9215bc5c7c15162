#include "link/session_recorder.hpp"

#include <fcntl.h>
#include <google/protobuf/io/zero_copy_stream_impl.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

#include "kapfix/v1/session.pb.h"
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
  EXPECT_EQ(reader.format(), "kapfix-session 1");
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
  EXPECT_TRUE(reader.error().empty()) << reader.error();
}

// The file is plain protobuf: read here with protobuf's own delimited reader, not ours.
TEST_F(LinkSessionRecordTest, FileIsLengthDelimitedSessionRecordsAnyProtobufClientReads) {
  {
    SessionRecorder recorder(File());
    recorder.Write("telemetry", "bytes", 7);
  }
  google::protobuf::io::FileInputStream in(::open(File().c_str(), O_RDONLY | O_CLOEXEC));
  in.SetCloseOnDelete(true);
  kapfix::v1::SessionRecord record;
  bool clean_eof = false;
  ASSERT_TRUE(google::protobuf::util::ParseDelimitedFromZeroCopyStream(&record, &in, &clean_eof));
  ASSERT_TRUE(record.has_format());
  EXPECT_EQ(record.format().name(), "kapfix-session");
  EXPECT_EQ(record.format().version(), 1U);
  EXPECT_EQ(record.format().protocol_version(), 1U);
  ASSERT_TRUE(google::protobuf::util::ParseDelimitedFromZeroCopyStream(&record, &in, &clean_eof));
  ASSERT_TRUE(record.has_message());
  EXPECT_EQ(record.message().receive_time_us(), 7);
  EXPECT_EQ(record.message().topic(), "telemetry");
  EXPECT_EQ(record.message().payload(), "bytes");
  EXPECT_FALSE(google::protobuf::util::ParseDelimitedFromZeroCopyStream(&record, &in, &clean_eof));
  EXPECT_TRUE(clean_eof);
}

// A topic is recorded as it came, even when it is not text.
TEST_F(LinkSessionRecordTest, TopicThatIsNotUtf8RoundTrips) {
  const std::string topic("\xff\xfe", 2);
  {
    SessionRecorder recorder(File());
    recorder.Write(topic, "x", 1);
  }
  SessionReader reader(File());
  const auto message = reader.Next();
  ASSERT_TRUE(message.has_value()) << reader.error();
  EXPECT_EQ(message->topic, topic);
}

TEST_F(LinkSessionRecordTest, RecorderRefusesAPathItCannotCreateNamingIt) {
  try {
    SessionRecorder recorder((folder_ / "missing" / "session.kfx").string());
    FAIL() << "a file in a missing folder was created";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("missing/session.kfx"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace kapfix::link
