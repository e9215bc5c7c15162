#include "agent/resume/resume_store.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/temp_dir.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix::agent {
namespace {

namespace fs = std::filesystem;
using kapfix::testing::TempDir;

ResumeRecord FixatingRecord() {
  ResumeRecord record;
  kapfix::v1::Command gains;
  gains.mutable_set_gains()->set_p(0.6F);
  record.settings.push_back(gains);
  kapfix::v1::Command interval;
  interval.mutable_set_photo()->set_interval_s(4.0F);
  record.settings.push_back(interval);
  record.mode = AgentMode::kFixate;
  record.slice = 3;
  record.reference_frame = kapfix::testing::LoadOpenCvPhoto("aero1.jpg");
  record.reference_at = {12.5, -3.0};
  return record;
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ResumeStoreTest, ARecordComesBackAsItWasSaved) {
  TempDir dir;
  const ResumeRecord saved = FixatingRecord();
  ResumeStore(dir.path()).Save(saved);
  std::string error;
  const std::optional<ResumeRecord> loaded = ResumeStore(dir.path()).Load(&error);
  ASSERT_TRUE(loaded.has_value()) << error;
  ASSERT_EQ(loaded->settings.size(), 2u);
  EXPECT_FLOAT_EQ(loaded->settings[0].set_gains().p(), 0.6F);
  EXPECT_FALSE(loaded->settings[0].set_gains().has_i());  // only what the command carried
  EXPECT_FLOAT_EQ(loaded->settings[1].set_photo().interval_s(), 4.0F);
  EXPECT_EQ(loaded->mode, AgentMode::kFixate);
  EXPECT_EQ(loaded->slice, 3);
  EXPECT_DOUBLE_EQ(loaded->reference_at.pan_deg, 12.5);
  EXPECT_DOUBLE_EQ(loaded->reference_at.tilt_deg, -3.0);
  ASSERT_EQ(loaded->reference_frame.size(), saved.reference_frame.size());
  EXPECT_EQ(cv::norm(loaded->reference_frame, saved.reference_frame, cv::NORM_INF), 0.0)
      << "the reference must come back pixel for pixel (PNG)";
}

TEST(ResumeStoreTest, NothingStoredIsNoRecordAndNoError) {
  TempDir dir;
  std::string error = "untouched";
  EXPECT_FALSE(ResumeStore(dir.path() / "resume").Load(&error).has_value());
  EXPECT_TRUE(error.empty()) << error;
}

TEST(ResumeStoreTest, ATruncatedFileIsRefusedWithAReasonNamingIt) {
  TempDir dir;
  ResumeStore store(dir.path());
  store.Save(FixatingRecord());
  const std::string text = ReadText(store.file());
  std::ofstream(store.file(), std::ios::trunc) << text.substr(0, text.size() / 2);
  std::string error;
  EXPECT_FALSE(ResumeStore(dir.path()).Load(&error).has_value());
  EXPECT_NE(error.find("resume.json"), std::string::npos) << error;
  EXPECT_NE(error.find("not valid JSON"), std::string::npos) << error;
}

TEST(ResumeStoreTest, AMissingReferenceImageIsRefused) {
  TempDir dir;
  ResumeStore store(dir.path());
  store.Save(FixatingRecord());
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    if (entry.path().extension() == ".png") fs::remove(entry.path());
  }
  std::string error;
  EXPECT_FALSE(ResumeStore(dir.path()).Load(&error).has_value());
  EXPECT_NE(error.find("reference image"), std::string::npos) << error;
}

TEST(ResumeStoreTest, AnUnknownModeIsRefused) {
  TempDir dir;
  ResumeStore store(dir.path());
  store.Save(FixatingRecord());
  std::string text = ReadText(store.file());
  text.replace(text.find("\"fixate\""), 8, "\"hover\"");
  std::ofstream(store.file(), std::ios::trunc) << text;
  std::string error;
  EXPECT_FALSE(ResumeStore(dir.path()).Load(&error).has_value());
  EXPECT_NE(error.find("unknown mode 'hover'"), std::string::npos) << error;
}

TEST(ResumeStoreTest, ANewReferenceReplacesTheOldImageOnDisk) {
  TempDir dir;
  ResumeStore store(dir.path());
  ResumeRecord record = FixatingRecord();
  store.Save(record);
  record.reference_frame = kapfix::testing::LoadOpenCvPhoto("aero3.jpg");
  store.Save(record);
  int images = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    images += entry.path().extension() == ".png" ? 1 : 0;
  }
  EXPECT_EQ(images, 1);
  std::string error;
  const auto loaded = ResumeStore(dir.path()).Load(&error);
  ASSERT_TRUE(loaded.has_value()) << error;
  EXPECT_EQ(cv::norm(loaded->reference_frame, record.reference_frame, cv::NORM_INF), 0.0);
}

TEST(ResumeStoreTest, SetAsideMovesTheFileSoItIsNotReadAgain) {
  TempDir dir;
  ResumeStore store(dir.path());
  store.Save(FixatingRecord());
  const fs::path aside = store.SetAside();
  EXPECT_EQ(aside.filename(), "resume.json.bad");
  EXPECT_TRUE(fs::exists(aside));
  std::string error;
  EXPECT_FALSE(store.Load(&error).has_value());
  EXPECT_TRUE(error.empty()) << error;
}

}  // namespace
}  // namespace kapfix::agent
