#include "agent/resume/stored_settings.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

TEST(StoredSettingsTest, StoredSettingsApplyOverTheConfiguration) {
  AgentConfig config;
  kapfix::v1::Command gains;
  gains.mutable_set_gains()->set_p(0.6F);
  kapfix::v1::Command search;
  search.mutable_set_search()->set_patch_size_px(60);
  std::string error;
  ASSERT_TRUE(ApplyStoredSettings({gains, search}, &config, &error)) << error;
  EXPECT_NEAR(config.gains.p(), 0.6, 1e-6);
  EXPECT_EQ(config.search.patch_px, 60);
}

TEST(StoredSettingsTest, AStoredValueOutOfRangeIsRefusedByTheSchemaAndChangesNothing) {
  AgentConfig config;
  const double kp = config.gains.p();
  kapfix::v1::Command good;
  good.mutable_set_gains()->set_i(0.1F);
  kapfix::v1::Command bad;
  bad.mutable_set_gains()->set_p(99.0F);
  std::string error;
  EXPECT_FALSE(ApplyStoredSettings({good, bad}, &config, &error));
  EXPECT_NE(error.find("set_gains.p"), std::string::npos) << error;
  EXPECT_DOUBLE_EQ(config.gains.p(), kp);
  EXPECT_DOUBLE_EQ(config.gains.i(), AgentConfig{}.gains.i());
}

TEST(StoredSettingsTest, ACorruptRecordIsSetAsideAndTheConfigurationStands) {
  TempDir dir;
  ResumeStore store(dir.path());
  std::ofstream(store.file()) << "{\"format\": 1, \"mode\": \"fix";  // cut short
  AgentConfig config;
  config.gains.set_p(0.9F);
  EXPECT_FALSE(LoadResumeRecord(store, &config).has_value());
  EXPECT_FLOAT_EQ(config.gains.p(), 0.9F);
  EXPECT_FALSE(std::filesystem::exists(store.file()));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "resume.json.bad"));
}

TEST(StoredSettingsTest, ARecordWhoseSettingFailsIsSetAsideToo) {
  TempDir dir;
  ResumeStore store(dir.path());
  ResumeRecord record;
  kapfix::v1::Command bad;
  bad.mutable_set_gains()->set_p(-1.0F);
  record.settings.push_back(bad);
  store.Save(record);
  AgentConfig config;
  EXPECT_FALSE(LoadResumeRecord(store, &config).has_value());
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "resume.json.bad"));
}

TEST(StoredSettingsTest, NoRecordIsAFreshStartWithNothingSetAside) {
  TempDir dir;
  ResumeStore store(dir.path());
  AgentConfig config;
  EXPECT_FALSE(LoadResumeRecord(store, &config).has_value());
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "resume.json.bad"));
}

}  // namespace
}  // namespace kapfix::agent
