#include "agent/server/command_intake.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string_view>

#include "tests/link/fake_agent_control.hpp"

namespace kapfix::agent {
namespace {

using kapfix::v1::Command;

constexpr std::string_view kStation = "station-1";

Command SelectSlice(std::uint64_t sequence, std::uint32_t slice) {
  Command command;
  kapfix::v1::Stamp(command.mutable_header(), "kapfix-agent", sequence);
  command.set_select_slice(slice);
  return command;
}

class CommandIntakeTest : public ::testing::Test {
 protected:
  CommandIntake::Outcome Answer(const Command& command) {
    return intake_.Answer(kStation, "command", command.SerializeAsString());
  }

  kapfix::testing::FakeAgentControl control_;
  CommandIntake intake_{control_, "kapfix-agent"};
};

TEST_F(CommandIntakeTest, AcceptedCommandIsExecutedAndItsSequenceReported) {
  const auto outcome = Answer(SelectSlice(7, 3));
  EXPECT_TRUE(outcome.reply.ok());
  EXPECT_EQ(outcome.command_sequence, 7U);
  ASSERT_EQ(control_.commands().size(), 1U);
  EXPECT_EQ(control_.commands().front().select_slice(), 3U);
}

TEST_F(CommandIntakeTest, CommandRefusedByTheRangeCheckStillShowsTheStationIsAlive) {
  const auto outcome = Answer(SelectSlice(1, 99));
  EXPECT_EQ(outcome.reply.error(), kapfix::v1::ERROR_CODE_OUT_OF_RANGE);
  EXPECT_TRUE(outcome.station_heard);
  EXPECT_TRUE(control_.commands().empty());
}

TEST_F(CommandIntakeTest, UnreadableBytesDoNotShowTheStationIsAlive) {
  const auto outcome = intake_.Answer(kStation, std::nullopt, "\xff\xff\xff");
  EXPECT_EQ(outcome.reply.error(), kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_FALSE(outcome.station_heard);
  EXPECT_EQ(outcome.command_sequence, 0U);
}

TEST_F(CommandIntakeTest, WrongVersionRefusalStillNamesTheCommandsSequence) {
  Command command = SelectSlice(5, 3);
  command.mutable_header()->set_protocol_version(kapfix::v1::kProtocolVersion + 1);
  const auto outcome = Answer(command);
  EXPECT_EQ(outcome.reply.error(), kapfix::v1::ERROR_CODE_WRONG_VERSION);
  EXPECT_EQ(outcome.command_sequence, 5U);
}

TEST_F(CommandIntakeTest, SequencesAreCheckedPerSender) {
  EXPECT_TRUE(Answer(SelectSlice(4, 3)).reply.ok());
  EXPECT_EQ(Answer(SelectSlice(4, 3)).reply.error(), kapfix::v1::ERROR_CODE_STALE_SEQUENCE);
  EXPECT_TRUE(
      intake_.Answer("station-2", "command", SelectSlice(4, 3).SerializeAsString()).reply.ok());
}

}  // namespace
}  // namespace kapfix::agent
