#include "agent/capture/camera_setting_controls.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kapfix::agent {
namespace {

using kapfix::v1::CameraSettings;

// Controls that record what reached them.
struct Recorder {
  std::vector<double> gains;
  std::vector<double> exposures;
  CameraSettingControls Controls() {
    CameraSettingControls controls;
    controls.Add(CameraSettings::kGainDbFieldNumber, [this](double db, std::string*) {
      gains.push_back(db);
      return true;
    });
    controls.Add(CameraSettings::kExposureUsFieldNumber, [this](double us, std::string*) {
      exposures.push_back(us);
      return true;
    });
    return controls;
  }
};

TEST(CameraSettingControlsTest, EachSetFieldReachesItsControl) {
  Recorder recorder;
  CameraSettings settings;
  settings.set_gain_db(6);
  settings.set_exposure_us(2500);
  std::string error;
  EXPECT_TRUE(recorder.Controls().Apply(settings, "test camera", &error)) << error;
  EXPECT_EQ(recorder.gains, std::vector<double>{6});
  EXPECT_EQ(recorder.exposures, std::vector<double>{2500});
}

TEST(CameraSettingControlsTest, AnUnsetFieldIsLeftToTheCamera) {
  Recorder recorder;
  CameraSettings settings;
  settings.set_gain_db(6);
  EXPECT_TRUE(recorder.Controls().Apply(settings, "test camera", nullptr));
  EXPECT_TRUE(recorder.exposures.empty());
}

TEST(CameraSettingControlsTest, ASettingWithoutAControlIsRefusedNamingItAndTheCamera) {
  Recorder recorder;
  CameraSettings settings;
  settings.set_auto_exposure(true);
  std::string error;
  EXPECT_FALSE(recorder.Controls().Apply(settings, "test camera", &error));
  EXPECT_EQ(error, "test camera: auto_exposure = true: this camera has no such control");
}

TEST(CameraSettingControlsTest, ARefusedSettingIsNamedWithItsValueUnitAndReason) {
  CameraSettingControls controls;
  controls.Add(CameraSettings::kGainDbFieldNumber, [](double, std::string* reason) {
    *reason = "outside its range [0, 24] dB";
    return false;
  });
  CameraSettings settings;
  settings.set_gain_db(30);
  std::string error;
  EXPECT_FALSE(controls.Apply(settings, "test camera", &error));
  EXPECT_EQ(error, "test camera: gain_db = 30 dB: outside its range [0, 24] dB");
}

TEST(CameraSettingControlsTest, ARefusedSettingDoesNotStopTheOthers) {
  Recorder recorder;
  CameraSettingControls controls;
  controls.Add(CameraSettings::kGainDbFieldNumber, [](double, std::string* reason) {
    *reason = "no";
    return false;
  });
  controls.Add(CameraSettings::kExposureUsFieldNumber, [&recorder](double us, std::string*) {
    recorder.exposures.push_back(us);
    return true;
  });
  CameraSettings settings;
  settings.set_gain_db(6);
  settings.set_exposure_us(2500);
  EXPECT_FALSE(controls.Apply(settings, "test camera", nullptr));
  EXPECT_EQ(recorder.exposures, std::vector<double>{2500});
}

TEST(CameraSettingControlsTest, EveryRefusalIsInTheOneLine) {
  CameraSettingControls none;
  CameraSettings settings;
  settings.set_gain_db(6);
  settings.set_auto_exposure(true);
  std::string error;
  EXPECT_FALSE(none.Apply(settings, "test camera", &error));
  EXPECT_NE(error.find("gain_db = 6 dB"), std::string::npos) << error;
  EXPECT_NE(error.find("; auto_exposure = true"), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace
}  // namespace kapfix::agent
