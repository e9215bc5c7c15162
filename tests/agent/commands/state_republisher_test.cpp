// StateRepublisher: a state lost on the link heals by itself.
#include "agent/commands/state_republisher.hpp"

#include <gtest/gtest.h>

#include "tests/agent/support/recording_stream_sink.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::RecordingStreamSink;
using kapfix::agent::testing::WaitUntil;

TEST(StateRepublisherTest, ALostStateIsPublishedAgainWithoutAnotherChange) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  sink.RefuseNext(1);  // the link drops the state of this change
  AgentConfig settings;
  settings.gains.set_p(0.75F);
  keeper.SetSettings(settings);
  ASSERT_TRUE(sink.Messages<kapfix::v1::AgentState>().empty());

  const StateRepublisher republisher(keeper, std::chrono::milliseconds(1));
  EXPECT_TRUE(WaitUntil([&sink] {
    const auto states = sink.Messages<kapfix::v1::AgentState>();
    return !states.empty() && states.back().gains().p() == 0.75F;
  }));
}

TEST(StateRepublisherTest, StopsWhenDestroyed) {
  RecordingStreamSink sink;
  StateKeeper keeper(AgentConfig{}, sink, true, nullptr);
  {
    // A long interval: destruction must not wait for it.
    const StateRepublisher republisher(keeper, std::chrono::hours(1));
  }
  EXPECT_EQ(sink.size(), 0u);
}

}  // namespace
}  // namespace kapfix::agent
