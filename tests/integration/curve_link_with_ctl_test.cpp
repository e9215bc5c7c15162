// Issue 5's keys end to end: kapfix-keygen makes the key files, kapfix-agent loads them from
// its configuration, and kapfix-ctl gets in only with an authorised key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/integration/agent_process.hpp"
#include "tests/link/link_test_support.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;

class CurveLinkWithCtlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {"agent", "laptop", "stranger"}) {
      const ProcessOutcome made =
          RunProcess(std::string(KAPFIX_KEYGEN) + " " + name + " --dir " + keys_.path().string(),
                     keys_.path() / "keygen.err");
      ASSERT_EQ(made.exit_code, 0) << made.err;
    }
    std::ofstream(keys_.path() / "authorized_keys") << "# stations allowed to fly this agent\n"
                                                    << ReadFile(keys_.path() / "laptop.pub");
    std::ofstream(keys_.path() / "agent.json")
        << R"({"link": {"curve_secret_key_file": ")" << (keys_.path() / "agent.key").string()
        << R"(", "curve_authorized_keys_file": ")" << (keys_.path() / "authorized_keys").string()
        << R"("}})";
  }

  std::string KeysOf(const std::string& station) const {
    return "--key " + (keys_.path() / (station + ".key")).string() + " --agent-key " +
           (keys_.path() / "agent.pub").string() + " ";
  }
  std::vector<std::string> AgentArguments() const {
    return {"--config", (keys_.path() / "agent.json").string(), "--mode", "idle"};
  }

  TempDir keys_;
};

TEST_F(CurveLinkWithCtlTest, KeygenWritesTheSecretKeyWithMode0600) {
  struct stat info {};
  ASSERT_EQ(::stat((keys_.path() / "laptop.key").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777U, 0600U);
}

TEST_F(CurveLinkWithCtlTest, KeygenRefusesToReplaceAnExistingKey) {
  const ProcessOutcome again =
      RunProcess(std::string(KAPFIX_KEYGEN) + " laptop --dir " + keys_.path().string(),
                 keys_.path() / "again.err");
  EXPECT_NE(again.exit_code, 0);
  EXPECT_THAT(again.err, HasSubstr("already exists"));
}

TEST_F(CurveLinkWithCtlTest, AuthorisedStationCommandsTheAgent) {
  AgentProcess agent(AgentArguments());
  const auto status = agent.Ctl(KeysOf("laptop") + "status");
  EXPECT_EQ(status.exit_code, 0) << status.err << agent.log();
  EXPECT_THAT(status.out, HasSubstr("mode: idle"));
  EXPECT_THAT(agent.log(), HasSubstr("CurveZMQ, 1 authorised station key"));
}

TEST_F(CurveLinkWithCtlTest, UnknownStationIsRefusedAndToldWhy) {
  AgentProcess agent(AgentArguments());
  const auto status = agent.Ctl(KeysOf("stranger") + "status");
  EXPECT_EQ(status.exit_code, 3) << status.out;
  EXPECT_THAT(status.err, HasSubstr("refused this station's key"));
  EXPECT_THAT(agent.log(), HasSubstr("unknown station key"));
}

TEST_F(CurveLinkWithCtlTest, StationWithoutKeysGetsNoAnswer) {
  AgentProcess agent(AgentArguments());
  const auto status = agent.Ctl("status");
  EXPECT_EQ(status.exit_code, 3) << status.out;
  EXPECT_THAT(status.err, HasSubstr("security handshake"));
}

TEST_F(CurveLinkWithCtlTest, AgentRefusesToStartWithAnUnprotectedSecretKey) {
  ASSERT_EQ(::chmod((keys_.path() / "agent.key").c_str(), 0644), 0);
  AgentProcess agent(AgentArguments());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (agent.running() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_FALSE(agent.running()) << "the agent started with a secret key others can read";
  EXPECT_NE(agent.Stop(), 0);
  EXPECT_THAT(agent.log(), HasSubstr("chmod 600"));
}

}  // namespace
}  // namespace kapfix::testing
