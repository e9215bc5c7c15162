#include "common/sim/scene_camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

// Geometry only: no gain, blur or noise, so frames can be compared pixel for pixel.
SceneCameraOptions Clean() {
  SceneCameraOptions o;
  o.noise_sigma = 0;
  o.brightness_amplitude = 0;
  return o;
}

bool Identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

TEST(SceneCameraTest, CaptureIsABgrFrameOfTheConfiguredSize) {
  SceneCameraOptions o;
  o.frame_size = {320, 240};
  const SceneCamera camera(testing::LoadOpenCvPhoto("aero1.jpg"), o);
  const cv::Mat frame = camera.Capture(3, {12.5, -4.25});
  EXPECT_EQ(frame.size(), cv::Size(320, 240));
  EXPECT_EQ(frame.type(), CV_8UC3);
}

TEST(SceneCameraTest, LineOfSightRightMovesContentLeftByExactlyThatMuch) {
  const SceneCamera camera(testing::LoadOpenCvPhoto("aero1.jpg"), Clean());
  const cv::Mat base = camera.Capture(0, {0, 0});
  const int w = base.cols;
  for (int d : {1, 7, 40}) {
    const cv::Mat moved = camera.Capture(0, {static_cast<double>(d), 0});
    // A feature at x in `base` appears at x − d in `moved`.
    EXPECT_TRUE(Identical(moved.colRange(0, w - d), base.colRange(d, w))) << "d = " << d;
    EXPECT_FALSE(Identical(moved.colRange(d, w), base.colRange(0, w - d))) << "d = " << d;
  }
}

TEST(SceneCameraTest, LineOfSightDownMovesContentUpByExactlyThatMuch) {
  const SceneCamera camera(testing::LoadOpenCvPhoto("aero1.jpg"), Clean());
  const cv::Mat base = camera.Capture(0, {0, 0});
  const int h = base.rows;
  const cv::Mat moved = camera.Capture(0, {0, 9});
  EXPECT_TRUE(Identical(moved.rowRange(0, h - 9), base.rowRange(9, h)));
  const cv::Mat up = camera.Capture(0, {0, -9});
  EXPECT_TRUE(Identical(up.rowRange(9, h), base.rowRange(0, h - 9)));
}

TEST(SceneCameraTest, HalfPixelLineOfSightInterpolatesBetweenNeighbours) {
  // 600 − 300 is even, so the window at (0, 0) sits on whole scene pixels.
  const cv::Mat scene = testing::SmoothTexture({600, 600}, 5, 1.0);
  const SceneCamera camera(scene, Clean());
  const cv::Mat base = camera.Capture(0, {0, 0});
  const cv::Mat half = camera.Capture(0, {0.5, 0});
  const int w = base.cols;
  cv::Mat mean;
  cv::addWeighted(base.colRange(0, w - 1), 0.5, base.colRange(1, w), 0.5, 0, mean, CV_32F);
  cv::Mat half_f;
  half.colRange(0, w - 1).convertTo(half_f, CV_32F);
  EXPECT_LE(cv::norm(half_f, mean, cv::NORM_INF), 1.0);
  EXPECT_GT(cv::norm(half, base, cv::NORM_INF), 10.0);
}

TEST(SceneCameraTest, SameSeedAndFrameGiveIdenticalImages) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const SceneCamera a(scene, SceneCameraOptions{}), b(scene, SceneCameraOptions{});
  EXPECT_TRUE(Identical(a.Capture(17, {3.5, 1}), b.Capture(17, {3.5, 1})));
  a.Capture(18, {0, 0});  // no hidden state: other frames in between change nothing
  EXPECT_TRUE(Identical(a.Capture(17, {3.5, 1}), b.Capture(17, {3.5, 1})));
}

TEST(SceneCameraTest, NoiseDiffersBetweenFramesAndSeeds) {
  const cv::Mat scene(400, 400, CV_8UC3, cv::Scalar(128, 128, 128));
  SceneCameraOptions o;
  o.brightness_amplitude = 0;
  const SceneCamera a(scene, o);
  o.seed = 2;
  const SceneCamera b(scene, o);
  EXPECT_FALSE(Identical(a.Capture(5, {0, 0}), a.Capture(6, {0, 0})));
  EXPECT_FALSE(Identical(a.Capture(5, {0, 0}), b.Capture(5, {0, 0})));
}

TEST(SceneCameraTest, NoiseSigmaMeasuredOnAFlatSceneIsAsConfigured) {
  const cv::Mat scene(400, 400, CV_8UC3, cv::Scalar(128, 128, 128));
  SceneCameraOptions o;
  o.brightness_amplitude = 0;
  const SceneCamera camera(scene, o);
  cv::Scalar mean, sigma;
  cv::meanStdDev(camera.Capture(11, {0, 0}).reshape(1), mean, sigma);
  EXPECT_NEAR(mean[0], 128.0, 0.05);
  EXPECT_NEAR(sigma[0], 3.0, 0.05);  // rounding to 8 bit adds 1/12 grey level² of variance
}

TEST(SceneCameraTest, BrightnessDriftScalesTheMeanByTheGain) {
  SceneCameraOptions o = Clean();
  o.brightness_amplitude = 0.08;
  o.brightness_period_frames = 400;
  const SceneCamera camera(testing::LoadOpenCvPhoto("aero1.jpg"), o);
  EXPECT_DOUBLE_EQ(camera.BrightnessGain(100), 1.08);
  const double at_rest = cv::mean(camera.Capture(0, {0, 0}).reshape(1))[0];
  const double brightest = cv::mean(camera.Capture(100, {0, 0}).reshape(1))[0];
  const double darkest = cv::mean(camera.Capture(300, {0, 0}).reshape(1))[0];
  EXPECT_NEAR(brightest / at_rest, 1.08, 0.005);
  EXPECT_NEAR(darkest / at_rest, 0.92, 0.005);
}

TEST(SceneCameraTest, BlurRemovesFineDetail) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  SceneCameraOptions o = Clean();
  const SceneCamera sharp(scene, o);
  o.blur_sigma = 2.0;
  const SceneCamera blurred(scene, o);
  auto detail = [](const cv::Mat& bgr) {
    cv::Mat grey, lap;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    cv::Laplacian(grey, lap, CV_32F);
    cv::Scalar mean, sigma;
    cv::meanStdDev(lap, mean, sigma);
    return sigma[0];
  };
  EXPECT_LT(detail(blurred.Capture(0, {0, 0})), 0.5 * detail(sharp.Capture(0, {0, 0})));
}

double Detail(const cv::Mat& bgr) {
  cv::Mat grey, lap;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::Laplacian(grey, lap, CV_32F);
  cv::Scalar mean, sigma;
  cv::meanStdDev(lap, mean, sigma);
  return sigma[0];
}

TEST(SceneCameraTest, MotionBlurGrowsWithTheViewsSpeed) {
  SceneCameraOptions o = Clean();
  o.motion_blur_exposure = 0.5;
  const SceneCamera camera(testing::LoadOpenCvPhoto("aero1.jpg"), o);
  const double still = Detail(camera.Capture(0, {0, 0}, {0, 0}));
  const double slow = Detail(camera.Capture(0, {0, 0}, {4, 0}));
  const double fast = Detail(camera.Capture(0, {0, 0}, {16, 0}));
  EXPECT_LT(slow, 0.9 * still);
  EXPECT_LT(fast, 0.7 * slow);
}

TEST(SceneCameraTest, RollTurnsTheFrameAboutItsCentre) {
  SceneCameraOptions o = Clean();
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const SceneCamera level(scene, o);
  o.roll_max_deg = 5;
  const SceneCamera rolled(scene, o);
  EXPECT_DOUBLE_EQ(rolled.RollDeg(0), 0.0);  // the reference frame is level
  int frame = 1;
  while (std::abs(rolled.RollDeg(frame)) < 2.0 && frame < 200) ++frame;
  ASSERT_GE(std::abs(rolled.RollDeg(frame)), 2.0) << "roll never reached 2° in 200 frames";
  for (int f = 0; f < 400; ++f) EXPECT_LE(std::abs(rolled.RollDeg(f)), 5.0);
  const cv::Mat a = level.Capture(frame, {0, 0}), b = rolled.Capture(frame, {0, 0});
  // The centre stays, the corners move.
  const cv::Rect centre(140, 140, 20, 20), corner(0, 0, 40, 40);
  EXPECT_LT(cv::norm(a(centre), b(centre), cv::NORM_L1) / centre.area(),
            0.5 * cv::norm(a(corner), b(corner), cv::NORM_L1) / corner.area());
}

TEST(SceneCameraTest, ExposureStepsChangeTheMeanByAtMostTheirShare) {
  SceneCameraOptions o = Clean();
  o.exposure_step_max = 0.2;
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero1.jpg");
  const SceneCamera camera(scene, o);
  EXPECT_DOUBLE_EQ(camera.ExposureGain(0), 1.0);
  bool stepped = false;
  for (int f = 0; f < 2000; f += 25) {
    EXPECT_LE(std::abs(camera.ExposureGain(f) - 1.0), 0.2);
    stepped = stepped || std::abs(camera.ExposureGain(f) - 1.0) > 0.05;
  }
  EXPECT_TRUE(stepped);
  int f = 125;
  while (std::abs(camera.ExposureGain(f) - 1.0) < 0.05) f += 125;
  const double ratio =
      cv::mean(camera.Capture(f, {0, 0}))[0] / cv::mean(camera.Capture(0, {0, 0}))[0];
  EXPECT_NEAR(ratio, camera.ExposureGain(f), 0.03);
}

TEST(SceneCameraTest, LargeEnoughSceneIsNotUpscaled) {
  SceneCameraOptions o;
  o.frame_size = {200, 200};
  o.max_excursion_px = 100;
  const SceneCamera camera(testing::LoadOpenCvPhoto("aero1.jpg"), o);  // 640×480
  EXPECT_EQ(camera.upscale_factor(), 1.0);
  EXPECT_EQ(camera.scene_size(), cv::Size(640, 480));
}

TEST(SceneCameraTest, SmallSceneIsUpscaledToCoverFramePlusTwiceTheExcursion) {
  const SceneCamera camera(cv::Mat(80, 100, CV_8UC3, cv::Scalar(1, 2, 3)), SceneCameraOptions{});
  EXPECT_GT(camera.upscale_factor(), 1.0);
  EXPECT_GE(camera.scene_size().width, 300 + 2 * 130);
  EXPECT_GE(camera.scene_size().height, 300 + 2 * 130);
  // Proportions kept: 100×80 stays 5:4 (up to the rounding of one pixel).
  EXPECT_NEAR(camera.scene_size().width * 0.8, camera.scene_size().height, 1.0);
  // A tall, narrow scene is limited by its width.
  const SceneCamera narrow(cv::Mat(2000, 100, CV_8UC3, cv::Scalar(1, 2, 3)), SceneCameraOptions{});
  EXPECT_DOUBLE_EQ(narrow.upscale_factor(), 5.6);
  EXPECT_GE(narrow.scene_size().width, 560);
}

TEST(SceneCameraTest, UpscaledSceneShowsNoBorderGarbageAtAnyExcursion) {
  // Blue is constant and green/red stay in [60, 200]: a black, white or uninitialised
  // pixel anywhere would break one of those.
  cv::Mat scene(80, 100, CV_8UC3);
  for (int y = 0; y < scene.rows; ++y) {
    for (int x = 0; x < scene.cols; ++x) {
      scene.at<cv::Vec3b>(y, x) =
          cv::Vec3b(77, static_cast<uchar>(60 + x), static_cast<uchar>(60 + 2 * y));
    }
  }
  const SceneCamera camera(scene, Clean());
  ASSERT_GT(camera.upscale_factor(), 1.0);
  for (double e : {130.0, 400.0, 1e7}) {
    for (cv::Point2d los :
         {cv::Point2d(e, e), cv::Point2d(-e, -e), cv::Point2d(e, -e), cv::Point2d(-e, 0.5)}) {
      std::vector<cv::Mat> planes;
      cv::split(camera.Capture(0, los), planes);
      double lo = 0, hi = 0;
      cv::minMaxLoc(planes[0], &lo, &hi);
      EXPECT_EQ(lo, 77) << los;
      EXPECT_EQ(hi, 77) << los;
      for (int c : {1, 2}) {
        cv::minMaxLoc(planes[static_cast<std::size_t>(c)], &lo, &hi);
        EXPECT_GE(lo, 60) << los;
        EXPECT_LE(hi, 60 + 2 * 79) << los;
      }
    }
  }
}

TEST(SceneCameraTest, CaptureIsTheSceneWindowCentredOnTheLineOfSight) {
  // A scene of exactly frame + 2·excursion: at ±excursion the window touches the scene's
  // edges and is still made of scene pixels only.
  cv::Mat scene;
  cv::cvtColor(testing::SmoothTexture({560, 560}, 8, 1.0), scene, cv::COLOR_GRAY2BGR);
  const SceneCamera camera(scene, Clean());
  ASSERT_EQ(camera.upscale_factor(), 1.0);
  EXPECT_TRUE(Identical(camera.Capture(0, {0, 0}), scene(cv::Rect(130, 130, 300, 300))));
  EXPECT_TRUE(Identical(camera.Capture(0, {130, 130}), scene(cv::Rect(260, 260, 300, 300))));
  EXPECT_TRUE(Identical(camera.Capture(0, {-130, -130}), scene(cv::Rect(0, 0, 300, 300))));
  EXPECT_TRUE(Identical(camera.Capture(0, {-130, 25}), scene(cv::Rect(0, 155, 300, 300))));
}

TEST(SceneCameraTest, GreySceneIsCapturedAsBgr) {
  const SceneCamera camera(testing::SmoothTexture({600, 600}, 4), Clean());
  const cv::Mat frame = camera.Capture(0, {0, 0});
  ASSERT_EQ(frame.type(), CV_8UC3);
  std::vector<cv::Mat> planes;
  cv::split(frame, planes);
  EXPECT_EQ(cv::norm(planes[0], planes[2], cv::NORM_INF), 0);
}

TEST(SceneCameraTest, EmptySceneThrowsWithAClearMessage) {
  try {
    SceneCamera camera(cv::Mat(), SceneCameraOptions{});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
  }
}

TEST(SceneCameraTest, BadOptionsAreRejected) {
  SceneCameraOptions o;
  o.frame_size = {0, 300};
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("frame size"), std::string::npos) << error;
  EXPECT_THROW(SceneCamera(cv::Mat(10, 10, CV_8UC3), o), std::invalid_argument);
  o = SceneCameraOptions{};
  o.brightness_amplitude = 1.0;
  EXPECT_FALSE(o.IsValid(nullptr));
  o = SceneCameraOptions{};
  o.noise_sigma = -1;
  EXPECT_FALSE(o.IsValid(nullptr));
  EXPECT_THROW(SceneCamera(cv::Mat(10, 10, CV_32FC3), SceneCameraOptions{}), std::invalid_argument);
}

TEST(SceneCameraTest, NonFiniteLineOfSightThrows) {
  const SceneCamera camera(cv::Mat(10, 10, CV_8UC3, cv::Scalar::all(9)), Clean());
  EXPECT_THROW(camera.Capture(0, {std::nan(""), 0}), std::invalid_argument);
  EXPECT_THROW(camera.Capture(0, {0, INFINITY}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
