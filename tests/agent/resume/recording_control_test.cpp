#include "agent/resume/recording_control.hpp"

#include <gtest/gtest.h>

#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

// Answers every command with `ok`.
class AnsweringControl : public AgentControl {
 public:
  bool ok = true;
  int executed = 0;
  kapfix::v1::Reply Execute(const kapfix::v1::Command& /*command*/) override {
    ++executed;
    kapfix::v1::Reply reply;
    reply.set_ok(ok);
    return reply;
  }
  kapfix::v1::AgentState State() const override { return {}; }
};

class IgnoringModeEvents : public ModeEvents {
 public:
  void OnModeChanged(AgentMode /*mode*/, int /*slice*/) override {}
  void OnSliceReport(const kapfix::v1::SliceReport& /*report*/) override {}
  void OnPssReport(const kapfix::v1::PssReport& /*report*/) override {}
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& /*report*/,
                           const std::optional<LensCalibration>& /*applied*/) override {}
  void OnFreeSwingRecorded(const std::string& /*path*/, const std::string& /*error*/) override {}
};

TEST(RecordingControlTest, OnlySettingsCommandsThatWereCarriedOutAreRecorded) {
  TempDir dir;
  ResumeStore store(dir.path());
  IgnoringModeEvents events;
  ResumeRecorder recorder(store, events, {}, "default");
  AnsweringControl agent;
  RecordingControl control(agent, recorder);

  kapfix::v1::Command refused;
  refused.mutable_set_gains()->set_p(0.5F);
  agent.ok = false;
  EXPECT_FALSE(control.Execute(refused).ok());
  kapfix::v1::Command photo;
  photo.mutable_take_photo();
  agent.ok = true;
  EXPECT_TRUE(control.Execute(photo).ok());
  kapfix::v1::Command accepted;
  accepted.mutable_set_gains()->set_p(0.8F);
  EXPECT_TRUE(control.Execute(accepted).ok());
  recorder.Flush();
  EXPECT_EQ(agent.executed, 3);

  std::string error;
  const auto record = ResumeStore(dir.path()).Load(&error);
  ASSERT_TRUE(record.has_value()) << error;
  ASSERT_EQ(record->settings.size(), 1u);
  EXPECT_FLOAT_EQ(record->settings[0].set_gains().p(), 0.8F);
  EXPECT_EQ(recorder.writes(), 1u);
}

}  // namespace
}  // namespace kapfix::agent
