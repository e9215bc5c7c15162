// The fuzzers' kept corpus (tests/fuzz/corpus) run through the same entry points as the
// fuzzers, in the normal build: any input that once broke an invariant and was fixed stays
// fixed, and the seeds prove the entry points still accept what is valid and refuse what is
// not. An input breaking an invariant aborts the test.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/topic_table.hpp"
#include "tests/fuzz/fuzz_entry_points.hpp"

namespace kapfix::fuzz {
namespace {

struct CorpusFile {
  std::string name;
  std::vector<std::uint8_t> bytes;
};

std::vector<CorpusFile> ReadCorpus(const std::string& fuzzer) {
  const std::filesystem::path folder = std::filesystem::path(KAPFIX_FUZZ_CORPUS_DIR) / fuzzer;
  std::vector<CorpusFile> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    files.push_back({entry.path().filename().string(),
                     std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {})});
  }
  std::sort(files.begin(), files.end(),
            [](const CorpusFile& a, const CorpusFile& b) { return a.name < b.name; });
  return files;
}

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

std::vector<CorpusFile> Named(const std::vector<CorpusFile>& files, const std::string& prefix) {
  std::vector<CorpusFile> named;
  std::copy_if(files.begin(), files.end(), std::back_inserter(named),
               [&](const CorpusFile& file) { return StartsWith(file.name, prefix); });
  return named;
}

bool Contains(const std::vector<CorpusFile>& files, const std::string& name) {
  return std::any_of(files.begin(), files.end(),
                     [&](const CorpusFile& file) { return file.name == name; });
}

// Seeds written by seed_corpus_writer: at least so many valid and bad ones per fuzzer, so that
// an emptied or misplaced corpus fails rather than replays nothing.
constexpr std::size_t kMinValidSeeds = 10;
constexpr std::size_t kMinBadSeeds = 6;

class StreamCorpusReplayTest : public ::testing::Test {
 protected:
  const std::vector<CorpusFile> corpus_ = ReadCorpus("stream_message_decoding_fuzzer");
};

TEST_F(StreamCorpusReplayTest, HasAValidSeedForEveryTopic) {
  for (const std::string& topic : kapfix::link::Topics()) {
    EXPECT_TRUE(Contains(corpus_, "valid_" + topic)) << "no seed valid_" << topic;
  }
}

TEST_F(StreamCorpusReplayTest, EveryFileReplaysWithoutBreakingAnInvariant) {
  ASSERT_GE(corpus_.size(), kMinValidSeeds + kMinBadSeeds);
  for (const CorpusFile& file : corpus_) {
    SCOPED_TRACE(file.name);
    (void)FuzzStreamMessage(file.bytes.data(), file.bytes.size());
  }
}

TEST_F(StreamCorpusReplayTest, ValidSeedsAreDecoded) {
  const std::vector<CorpusFile> valid = Named(corpus_, "valid_");
  ASSERT_GE(valid.size(), kMinValidSeeds);
  for (const CorpusFile& file : valid) {
    EXPECT_TRUE(FuzzStreamMessage(file.bytes.data(), file.bytes.size())) << file.name;
  }
}

TEST_F(StreamCorpusReplayTest, BadSeedsAreRefused) {
  const std::vector<CorpusFile> bad = Named(corpus_, "bad_");
  ASSERT_GE(bad.size(), kMinBadSeeds);
  for (const CorpusFile& file : bad) {
    EXPECT_FALSE(FuzzStreamMessage(file.bytes.data(), file.bytes.size())) << file.name;
  }
}

class CommandCorpusReplayTest : public ::testing::Test {
 protected:
  const std::vector<CorpusFile> corpus_ = ReadCorpus("command_handling_fuzzer");
};

TEST_F(CommandCorpusReplayTest, HasAValidSeedForEveryCommandKind) {
  const auto* kinds = kapfix::v1::Command::descriptor()->FindOneofByName("command");
  ASSERT_NE(kinds, nullptr);
  for (int i = 0; i < kinds->field_count(); ++i) {
    const std::string& kind = kinds->field(i)->name();
    EXPECT_TRUE(Contains(corpus_, "valid_" + kind)) << "no seed valid_" << kind;
  }
}

TEST_F(CommandCorpusReplayTest, EveryFileReplaysWithoutBreakingAnInvariant) {
  ASSERT_GE(corpus_.size(), kMinValidSeeds + kMinBadSeeds);
  for (const CorpusFile& file : corpus_) {
    SCOPED_TRACE(file.name);
    (void)FuzzCommand(file.bytes.data(), file.bytes.size());
  }
}

TEST_F(CommandCorpusReplayTest, ValidSeedsAreExecuted) {
  const std::vector<CorpusFile> valid = Named(corpus_, "valid_");
  ASSERT_GE(valid.size(), kMinValidSeeds);
  for (const CorpusFile& file : valid) {
    EXPECT_EQ(FuzzCommand(file.bytes.data(), file.bytes.size()), kapfix::v1::ERROR_CODE_UNSPECIFIED)
        << file.name;
  }
}

TEST_F(CommandCorpusReplayTest, BadSeedsAreRefused) {
  const std::vector<CorpusFile> bad = Named(corpus_, "bad_");
  ASSERT_GE(bad.size(), kMinBadSeeds);
  for (const CorpusFile& file : bad) {
    EXPECT_NE(FuzzCommand(file.bytes.data(), file.bytes.size()), kapfix::v1::ERROR_CODE_UNSPECIFIED)
        << file.name;
  }
}

}  // namespace
}  // namespace kapfix::fuzz

namespace kapfix::fuzz {
namespace {

// The multipart target's input format, for a few requests built by hand.
std::vector<std::uint8_t> Frames(const std::vector<std::string>& frames) {
  std::vector<std::uint8_t> input;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i + 1 < frames.size()) input.push_back(static_cast<std::uint8_t>(frames[i].size()));
    input.insert(input.end(), frames[i].begin(), frames[i].end());
  }
  return input;
}

TEST(MultipartRequestTest, RequestsOfEveryShapeKeepTheInvariants) {
  const std::vector<std::vector<std::string>> shapes = {{"", "command", "x"},
                                                        {"command", "x"},
                                                        {"x"},
                                                        {"", "a", "b", "c"},
                                                        {"a", "b", "c", "d", "e", "f", "g", "h"}};
  for (const auto& shape : shapes) {
    const std::vector<std::uint8_t> input = Frames(shape);
    EXPECT_EQ(FuzzMultipartRequest(input.data(), input.size()), shape.size());
  }
  std::vector<std::uint8_t> many(2000, 0);  // 2,000 one-byte frames: refused, not kept
  EXPECT_EQ(FuzzMultipartRequest(many.data(), many.size()), 2000U);
}

// The subscription target's input format: records of peer byte, length, message.
std::vector<std::uint8_t> Records(
    const std::vector<std::pair<std::uint8_t, std::string>>& records) {
  std::vector<std::uint8_t> input;
  for (const auto& [peer, message] : records) {
    input.push_back(peer);
    input.push_back(static_cast<std::uint8_t>(message.size()));
    input.insert(input.end(), message.begin(), message.end());
  }
  return input;
}

TEST(SubscriptionSequenceTest, APeerGetsAtMostItsBoundOfSubscriptions) {
  std::vector<std::pair<std::uint8_t, std::string>> records;
  for (int i = 0; i < 10; ++i) records.emplace_back(0, "\x01topic" + std::to_string(i));
  const std::vector<std::uint8_t> input = Records(records);
  EXPECT_EQ(FuzzSubscriptions(input.data(), input.size()), 4U);  // the target's bound
}

TEST(SubscriptionSequenceTest, AnUnsubscriptionFreesASlot) {
  std::vector<std::pair<std::uint8_t, std::string>> records;
  for (int i = 0; i < 5; ++i) records.emplace_back(0, "\x01topic" + std::to_string(i));
  records.emplace_back(0, std::string(1, '\0') + "topic0");
  records.emplace_back(0, "\x01topic9");
  const std::vector<std::uint8_t> input = Records(records);
  EXPECT_EQ(FuzzSubscriptions(input.data(), input.size()), 5U);
}

// A subscription to topic "a" (ZMTP: 0x01, then the topic).
const std::string kSubscribeA = std::string("\x01") + "a";

TEST(SubscriptionSequenceTest, GonePeersMakeRoomForNewOnes) {
  // Three peers fill the book; a fourth is refused while they stay, admitted once one went.
  const std::vector<std::uint8_t> full =
      Records({{0, kSubscribeA}, {1, kSubscribeA}, {2, kSubscribeA}, {3, kSubscribeA}});
  EXPECT_EQ(FuzzSubscriptions(full.data(), full.size()), 3U);
  // Slot 0's connection closes (its new one sends no subscription).
  const std::vector<std::uint8_t> room = Records(
      {{0, kSubscribeA}, {1, kSubscribeA}, {2, kSubscribeA}, {0x80, "\x07"}, {3, kSubscribeA}});
  EXPECT_EQ(FuzzSubscriptions(room.data(), room.size()), 4U);
}

TEST(SubscriptionSequenceTest, EveryKeptFileReplaysWithoutBreakingAnInvariant) {
  const std::vector<CorpusFile> corpus = ReadCorpus("subscription_sequence_fuzzer");
  ASSERT_GE(corpus.size(), 5U);
  for (const CorpusFile& file : corpus) {
    SCOPED_TRACE(file.name);
    (void)FuzzSubscriptions(file.bytes.data(), file.bytes.size());
  }
}

}  // namespace
}  // namespace kapfix::fuzz
