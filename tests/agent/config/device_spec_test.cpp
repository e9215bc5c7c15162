#include "agent/config/device_spec.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

TEST(DeviceSpecTest, AravisAddressSelectsAravisWithThatDevice) {
  CameraConfig camera;
  std::string error;
  ASSERT_TRUE(ApplyCameraSpec("aravis:127.0.0.1", &camera, &error)) << error;
  EXPECT_EQ(camera.backend, CameraBackend::kAravis);
  EXPECT_EQ(camera.device, "127.0.0.1");
}

TEST(DeviceSpecTest, BareAravisMeansTheFirstCamera) {
  CameraConfig camera;
  camera.device = "old";
  ASSERT_TRUE(ApplyCameraSpec("aravis", &camera, nullptr));
  EXPECT_EQ(camera.device, "");
}

TEST(DeviceSpecTest, V4l2PathIsKept) {
  CameraConfig camera;
  ASSERT_TRUE(ApplyCameraSpec("v4l2:/dev/video2", &camera, nullptr));
  EXPECT_EQ(camera.backend, CameraBackend::kV4l2);
  EXPECT_EQ(camera.device, "/dev/video2");
}

TEST(DeviceSpecTest, UnknownCameraBackendIsNamedWithTheAcceptedForms) {
  CameraConfig camera;
  std::string error;
  EXPECT_FALSE(ApplyCameraSpec("gige:1.2.3.4", &camera, &error));
  EXPECT_EQ(camera.backend, CameraBackend::kSim);
  EXPECT_NE(error.find("--camera \"gige:1.2.3.4\": unknown camera backend \"gige\""),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("aravis:ID"), std::string::npos) << error;
}

TEST(DeviceSpecTest, V4l2WithoutDeviceIsRefused) {
  CameraConfig camera;
  std::string error;
  EXPECT_FALSE(ApplyCameraSpec("v4l2:", &camera, &error));
  EXPECT_NE(error.find("needs a device"), std::string::npos) << error;
}

TEST(DeviceSpecTest, MaestroPathSelectsTheMaestro) {
  ServoConfig servo;
  ASSERT_TRUE(ApplyServoSpec("maestro:/dev/kapfix-maestro", &servo, nullptr));
  EXPECT_EQ(servo.backend, ServoBackend::kMaestro);
  EXPECT_EQ(servo.device, "/dev/kapfix-maestro");
}

TEST(DeviceSpecTest, Pca9685TakesAHexAddress) {
  ServoConfig servo;
  ASSERT_TRUE(ApplyServoSpec("pca9685:/dev/i2c-1@0x41", &servo, nullptr));
  EXPECT_EQ(servo.backend, ServoBackend::kPca9685);
  EXPECT_EQ(servo.device, "/dev/i2c-1");
  EXPECT_EQ(servo.i2c_address, 0x41);
}

TEST(DeviceSpecTest, Pca9685AddressOutsideTheI2cRangeIsRefused) {
  ServoConfig servo;
  std::string error;
  EXPECT_FALSE(ApplyServoSpec("pca9685:/dev/i2c-1@0x80", &servo, &error));
  EXPECT_NE(error.find("0x03…0x77"), std::string::npos) << error;
  EXPECT_FALSE(ApplyServoSpec("pca9685:/dev/i2c-1@zz", &servo, &error));
  EXPECT_EQ(servo.backend, ServoBackend::kSim);
}

TEST(DeviceSpecTest, SimTakesNoDevice) {
  ServoConfig servo;
  std::string error;
  EXPECT_FALSE(ApplyServoSpec("sim:/dev/null", &servo, &error));
  EXPECT_NE(error.find("--servos \"sim:/dev/null\""), std::string::npos) << error;
}

}  // namespace
}  // namespace kapfix::agent
