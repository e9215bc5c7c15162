#include "common/control/servo_belief.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "common/control/proportional_controller.hpp"
#include "common/control/servo_belief_controller.hpp"
#include "common/sim/simulated_servo.hpp"

namespace kapfix {
namespace {

constexpr LensCalibration kLens{0.1, 0.1};  // [deg/px]

ControlInput Measured(double dx, double dy) {
  ControlInput input;
  input.displacement_px = {dx, dy};
  input.confidence = 0.9;
  input.found = true;
  input.dt_s = 0.04;
  return input;
}

// A servo whose latency jitters between 1 and 2 frames, with no play, dead band or speed
// limit to speak of: only the jitter is left for the belief to resolve.
SimulatedServoOptions JitteryServo() {
  SimulatedServoOptions options;
  options.latency_frames = 1;
  options.latency_max_frames = 2;
  options.backlash_deg = 0;
  options.dead_band_deg = 0;
  options.rate_limit_deg_per_frame = 50;
  options.seed = 7;
  return options;
}

// The jittery servo geared like a hobby servo: it turns at most 4 deg a frame, with 0.4 deg of
// play between shaft and output.
SimulatedServoOptions GearedServo() {
  SimulatedServoOptions options = JitteryServo();
  options.rate_limit_deg_per_frame = 4;
  options.backlash_deg = 0.4;
  return options;
}

// [px] a fast swing (80 px, 40 frames) that reverses every 20 frames.
double FastSwing(double t) { return 80 * std::sin(2 * std::numbers::pi * t / 40); }

TEST(ServoBeliefTest, AFixedLatencyBelievesTheCommandSentThatManyFramesBefore) {
  ServoBelief belief({.min_delay_frames = 2, .max_delay_frames = 2, .initial = {5, 6}});
  EXPECT_DOUBLE_EQ(belief.Expose(1).pan_deg, 5);  // nothing sent yet: the initial angles
  belief.Sent(0, {1, 2});
  belief.Sent(1, {3, 4});
  const ServoTargets at2 = belief.Expose(2);
  EXPECT_DOUBLE_EQ(at2.pan_deg, 1);
  EXPECT_DOUBLE_EQ(at2.tilt_deg, 2);
  EXPECT_DOUBLE_EQ(belief.Expose(3).tilt_deg, 4);
}

TEST(ServoBeliefTest, DelaySharesFavourShortDelaysWhenNewerCommandsOvertake) {
  const std::vector<double> one = DelayShares(1);
  ASSERT_EQ(one.size(), 2u);
  EXPECT_DOUBLE_EQ(one[0], 0.5);
  EXPECT_DOUBLE_EQ(one[1], 0.5);
  const std::vector<double> three = DelayShares(3);
  ASSERT_EQ(three.size(), 4u);
  EXPECT_DOUBLE_EQ(three[0], 0.25);
  EXPECT_DOUBLE_EQ(three[1], 0.375);
  EXPECT_DOUBLE_EQ(three[2], 0.28125);
  EXPECT_DOUBLE_EQ(three[3], 0.09375);
  EXPECT_EQ(DelayShares(0), std::vector<double>{1.0});
}

TEST(ServoBeliefTest, WithoutAMeasurementTheBeliefIsTheCandidatesWeightedMean) {
  ServoBelief belief({.min_delay_frames = 2, .max_delay_frames = 3, .initial = {0, 0}});
  belief.Sent(0, {0, 0});
  belief.Sent(1, {2, 4});
  belief.Expose(3);
  ControlInput lost;
  const ServoTargets believed = belief.Resolve(lost, kLens);
  EXPECT_DOUBLE_EQ(believed.pan_deg, 1);
  EXPECT_DOUBLE_EQ(believed.tilt_deg, 2);
}

// A servo whose latency jitters between 1 and 2 frames, following a swing-like command: the
// belief resolved from each frame's measurement is the servo's true angle, where the mean of
// the commands that may be in effect is wrong by half a frame's motion on every frame.
TEST(ServoBeliefTest, ResolvesTheCommandInEffectUnderLatencyJitter) {
  SimulatedServo servo(JitteryServo());
  ServoBelief belief({.min_delay_frames = 2, .max_delay_frames = 3, .initial = {0, 0}});
  const auto swing = [](double t) {  // [px] the platform's view, SPEC §3's swing
    return 100 * std::sin(2 * std::numbers::pi * t / 40);
  };
  int right = 0, counted = 0;
  double resolved_sq = 0, mean_sq = 0;
  for (int t = 0; t < 400; ++t) {
    if (t > 0) servo.Step();
    const double angle = servo.angle();
    // The content moves against the view: displacement = −(swing + servo's turn).
    const double dx = -(swing(t) + angle / kLens.pan_deg_per_px);
    const ServoTargets expected = belief.Expose(t);
    const ServoTargets resolved = belief.Resolve(Measured(dx, 0), kLens);
    if (t >= 10) {
      ++counted;
      // Within 0.2 px, where consecutive commands differ by up to 16 px.
      right += std::abs(resolved.pan_deg - angle) < 0.02 ? 1 : 0;
      resolved_sq += std::pow(resolved.pan_deg - angle, 2);
      mean_sq += std::pow(expected.pan_deg - angle, 2);
    }
    const double command = -swing(t + 2.5) * kLens.pan_deg_per_px;
    servo.Command(command);
    belief.Sent(t, {command, 0});
  }
  EXPECT_GE(right, counted * 95 / 100) << right << " of " << counted;
  EXPECT_LT(std::sqrt(resolved_sq / counted), 0.1 * std::sqrt(mean_sq / counted))
      << "resolved RMS " << std::sqrt(resolved_sq / counted) << " deg, mean's "
      << std::sqrt(mean_sq / counted) << " deg";
}

// The same servo and swing, but the calibration the belief is given is ×1.3 the true deg/px
// (the realistic world's): the views reconstructed with it keep 23 % of the servo's random
// early/late steps. The belief finds the scale that makes the views smooth and still
// resolves the command in effect.
TEST(ServoBeliefTest, FindsTheCalibrationScaleAndResolvesUnderJitterWithACalibrationOff) {
  SimulatedServo servo(JitteryServo());
  ServoBelief belief({.min_delay_frames = 2, .max_delay_frames = 3, .initial = {0, 0}});
  const LensCalibration off{1.3 * kLens.pan_deg_per_px, 1.3 * kLens.tilt_deg_per_px};
  const auto swing = [](double t) {  // [px] the platform's view, SPEC §3's swing
    return 100 * std::sin(2 * std::numbers::pi * t / 40);
  };
  int right = 0, counted = 0;
  for (int t = 0; t < 400; ++t) {
    if (t > 0) servo.Step();
    const double angle = servo.angle();
    const double dx = -(swing(t) + angle / kLens.pan_deg_per_px);
    belief.Expose(t);
    const ServoTargets resolved = belief.Resolve(Measured(dx, 0), off);
    if (t >= 10) {
      ++counted;
      right += std::abs(resolved.pan_deg - angle) < 0.02 ? 1 : 0;
    }
    // A loop acting on the calibration ×1.3 commands 1.3 × the angle the swing needs.
    const double command = -1.3 * swing(t + 2.5) * kLens.pan_deg_per_px;
    servo.Command(command);
    belief.Sent(t, {command, 0});
  }
  // 94 % (the first frames are resolved before the scale is found, and the grid's 1.26 or
  // 1.335 leaves a little of the steps); on the given calibration alone, 14 %.
  EXPECT_GE(right, counted * 90 / 100) << right << " of " << counted;
  // px per deg: the true 10 is 1.3 × the given calibration's 7.7; the grid steps by 6 %.
  EXPECT_NEAR(belief.scale(0), 1.3, 0.08);
  // Tilt never moved, so its views tell no scale; it looks through the same lens as pan.
  EXPECT_DOUBLE_EQ(belief.scale(1), belief.scale(0));
}

// The calibration ×1.3 off (the realistic world's) is found within the lock-on's first
// frames: every frame on the wrong scale lets the pull-in ring.
TEST(ServoBeliefTest, FindsACalibrationOffWithinTheFirstFramesOfTheLockOn) {
  SimulatedServo servo(JitteryServo());
  ServoBelief belief({.min_delay_frames = 2, .max_delay_frames = 3, .initial = {0, 0}});
  const LensCalibration off{1.3 * kLens.pan_deg_per_px, 1.3 * kLens.tilt_deg_per_px};
  const auto swing = [](double t) { return 100 * std::sin(2 * std::numbers::pi * t / 40); };
  int found_at = -1;  // the first frame from which the scale stays within a step of 1.3
  for (int t = 0; t < 100; ++t) {
    if (t > 0) servo.Step();
    const double dx = -(swing(t) + servo.angle() / kLens.pan_deg_per_px);
    belief.Expose(t);
    belief.Resolve(Measured(dx, 0), off);
    const bool near = std::abs(std::log(belief.scale(0) / 1.3)) < std::log(1.07);
    if (!near) found_at = -1;
    if (near && found_at < 0) found_at = t;
    const double command = -1.3 * swing(t + 2.5) * kLens.pan_deg_per_px;
    servo.Command(command);
    belief.Sent(t, {command, 0});
  }
  ASSERT_GE(found_at, 0) << "scale ends at " << belief.scale(0);
  EXPECT_LE(found_at, 10);
}

// Both axes through the jittery servo, the belief given the calibration ×`pan_off` (pan) and
// ×`tilt_off` (tilt) the true deg/px: pan's view swings 100 px, tilt's is `tilt_swing` [px]
// plus white noise of `tilt_noise_px` SD, and each axis's commands cancel what the loop
// would forecast through its calibration: the swing 2.5 frames ahead, or, for a noisy tilt,
// its last measured view, noise and all, as a loop does where the swing cannot be forecast.
struct TwoAxisFlight {
  double pan_off = 1.3;
  double tilt_off = 1.3;
  double (*tilt_swing)(double t) = nullptr;
  double tilt_noise_px = 0;
  double measurement_noise_px = 0.3;  // [px] SD on both axes, as a matcher's
  int frames = 400;

  ServoBelief Fly() const {
    SimulatedServo pan(JitteryServo());
    SimulatedServoOptions tilt_options = JitteryServo();
    tilt_options.seed = 11;
    SimulatedServo tilt(tilt_options);
    ServoBelief belief({.min_delay_frames = 2, .max_delay_frames = 3, .initial = {0, 0}});
    const LensCalibration given{pan_off * kLens.pan_deg_per_px, tilt_off * kLens.tilt_deg_per_px};
    const auto pan_swing = [](double t) { return 100 * std::sin(2 * std::numbers::pi * t / 40); };
    std::mt19937 random(5);
    std::normal_distribution<double> noise(0, tilt_noise_px > 0 ? tilt_noise_px : 1);
    std::normal_distribution<double> matcher(0, measurement_noise_px);
    for (int t = 0; t < frames; ++t) {
      if (t > 0) {
        pan.Step();
        tilt.Step();
      }
      const double tilt_view = tilt_swing(t) + (tilt_noise_px > 0 ? noise(random) : 0.0);
      const double dx = -(pan_swing(t) + pan.angle() / kLens.pan_deg_per_px) + matcher(random);
      const double dy = -(tilt_view + tilt.angle() / kLens.tilt_deg_per_px) + matcher(random);
      belief.Expose(t);
      belief.Resolve(Measured(dx, dy), given);
      const double tilt_aim = tilt_noise_px > 0 ? tilt_view : tilt_swing(t + 2.5);
      const ServoTargets command{-pan_swing(t + 2.5) * given.pan_deg_per_px,
                                 -tilt_aim * given.tilt_deg_per_px};
      pan.Command(command.pan_deg);
      tilt.Command(command.tilt_deg);
      belief.Sent(t, command);
    }
    return belief;
  }
};

// A realistic world's tilt: a small swing that is mostly noise the loop cannot forecast, and
// a servo that follows it. Its own views barely tell the scales apart, and they lean to the
// grid's end (the servo's turns cancel some of the noise); the lens is the one pan sees
// through, so tilt takes pan's scale.
TEST(ServoBeliefTest, AnAxisWhoseNoisySwingTellsLittleTakesTheOtherAxissScale) {
  TwoAxisFlight flight;
  flight.tilt_swing = [](double t) { return 5 * std::sin(2 * std::numbers::pi * t / 300); };
  flight.tilt_noise_px = 3;
  const ServoBelief belief = flight.Fly();
  EXPECT_NEAR(belief.scale(0), 1.3, 0.08);
  EXPECT_DOUBLE_EQ(belief.scale(1), belief.scale(0));
}

// Servos whose degrees differ per axis: with both axes swinging, each finds its own scale.
// (An axis keeps its own only while its views tell the scales apart at least a quarter as
// clearly as the other's; a far duller one takes the other's.)
TEST(ServoBeliefTest, TwoSwingingAxesKeepTheirOwnScales) {
  TwoAxisFlight flight;
  flight.tilt_off = 0.8;
  flight.tilt_swing = [](double t) { return 80 * std::sin(2 * std::numbers::pi * t / 55); };
  const ServoBelief belief = flight.Fly();
  EXPECT_NEAR(belief.scale(0), 1.3, 0.08);
  EXPECT_NEAR(belief.scale(1), 0.8, 0.05);
}

// A servo that turns at most 4 deg a frame, commands up to 3 deg a frame apart and a latency
// of 1…2 frames (the lock-on of the realistic world): when a late command is overtaken the
// one in effect jumps by up to 6 deg, and the servo shows an angle on the way to it. The
// belief told the servo's speed follows it there; taken as at the command it is up to 2 deg
// off on those frames.
TEST(ServoBeliefTest, AServoThatTurnsSlowerThanTheCommandsJumpIsBelievedOnItsWay) {
  SimulatedServoOptions slow = JitteryServo();
  slow.rate_limit_deg_per_frame = 4;
  const auto fly = [&slow](double max_step_deg) {
    SimulatedServo servo(slow);
    ServoBelief belief({.min_delay_frames = 2,
                        .max_delay_frames = 3,
                        .initial = {0, 0},
                        .max_step_deg = {max_step_deg, max_step_deg}});
    const auto swing = [](double t) {  // [px] up to 39 px/frame: commands rate-limited
      return 250 * std::sin(2 * std::numbers::pi * t / 40);
    };
    double worst = 0;  // [deg] the belief's largest miss of the servo's angle
    double command = 0;
    for (int t = 0; t < 120; ++t) {
      if (t > 0) servo.Step();
      const double dx = -(swing(t) + servo.angle() / kLens.pan_deg_per_px);
      belief.Expose(t);
      const ServoTargets resolved = belief.Resolve(Measured(dx, 0), kLens);
      if (t >= 3) worst = std::max(worst, std::abs(resolved.pan_deg - servo.angle()));
      // Rate-limited like the agent's commands: 3 deg a frame.
      const double wanted = -swing(t + 2.5) * kLens.pan_deg_per_px;
      command += std::clamp(wanted - command, -3.0, 3.0);
      servo.Command(command);
      belief.Sent(t, {command, 0});
    }
    return worst;
  };
  const double told = fly(4);
  const double untold = fly(std::numeric_limits<double>::infinity());
  EXPECT_LT(told, 0.1) << "told the servo's speed: " << told << " deg";
  EXPECT_GT(untold, 0.5) << "the set-up must make the servo lag its commands";
}

// A servo with play, driven through a swing's reversals: the output trails the shaft by
// half the play, so a belief that takes the output for the shaft is that far off on almost
// every frame, and one told the play follows the output.
TEST(ServoBeliefTest, AServoWithPlayIsBelievedAtItsOutputBehindTheShaft) {
  const SimulatedServoOptions geared = GearedServo();
  const auto fly = [&geared](double play_deg) {
    SimulatedServo servo(geared);
    ServoBelief belief({.min_delay_frames = 2,
                        .max_delay_frames = 3,
                        .initial = {0, 0},
                        .max_step_deg = {4, 4},
                        .play_deg = {play_deg, play_deg}});
    double miss_sq = 0;  // [deg²] the belief's miss of the servo's output, after the lock-on
    int counted = 0;
    for (int t = 0; t < 160; ++t) {
      if (t > 0) servo.Step();
      const double dx = -(FastSwing(t) + servo.angle() / kLens.pan_deg_per_px);
      belief.Expose(t);
      const ServoTargets resolved = belief.Resolve(Measured(dx, 0), kLens);
      if (t >= 20) {
        miss_sq += (resolved.pan_deg - servo.angle()) * (resolved.pan_deg - servo.angle());
        ++counted;
      }
      const double command = -FastSwing(t + 2.5) * kLens.pan_deg_per_px;
      servo.Command(command);
      belief.Sent(t, {command, 0});
    }
    return std::sqrt(miss_sq / counted);
  };
  const double told = fly(0.4);
  const double untold = fly(0);
  EXPECT_LT(told, 0.05) << "told the servo's play: " << told << " deg RMS";
  EXPECT_GT(untold, 0.15) << "not told, half the 0.4 deg play: " << untold << " deg RMS";
}

// A servo with 0.4 deg of play and a fixed latency, aimed at a swing: the output ends where
// the loop aims it only when the shaft is sent half the play beyond the aim on the side the
// output moves to (ShaftCommand); sent to the aim itself, the output stops half the play
// (2 px) short on every move.
TEST(ServoBeliefTest, AShaftCommandBringsTheOutputThroughThePlayToTheAim) {
  SimulatedServoOptions geared = GearedServo();
  geared.latency_max_frames = geared.latency_frames;
  const auto fly = [&geared](bool through_the_play) {
    SimulatedServo servo(geared);
    ServoBelief belief({.min_delay_frames = 2,
                        .max_delay_frames = 2,
                        .initial = {0, 0},
                        .max_step_deg = {4, 4},
                        .play_deg = {0.4, 0.4}});
    double miss_sq = 0;  // [px²] the view error, after the lock-on
    int counted = 0;
    for (int t = 0; t < 160; ++t) {
      if (t > 0) servo.Step();
      const double view_px = FastSwing(t) + servo.angle() / kLens.pan_deg_per_px;
      if (t >= 20) {
        miss_sq += view_px * view_px;
        ++counted;
      }
      belief.Expose(t);
      belief.Resolve(Measured(-view_px, 0), kLens);
      const ServoTargets aim{-FastSwing(t + 2) * kLens.pan_deg_per_px, 0};
      const ServoTargets command = through_the_play ? belief.ShaftCommand(aim) : aim;
      servo.Command(command.pan_deg);
      belief.Sent(t, command);
    }
    return std::sqrt(miss_sq / counted);
  };
  const double through = fly(true);
  const double at_the_aim = fly(false);
  EXPECT_LT(through, 0.5) << "through the play: " << through << " px RMS";
  EXPECT_GT(at_the_aim, 1.5) << "at the aim: " << at_the_aim << " px RMS";
}

TEST(ServoBeliefTest, AShaftCommandLeadsTheAimByHalfThePlayOnTheSideTheOutputMoves) {
  ServoBelief belief({.min_delay_frames = 1,
                      .max_delay_frames = 1,
                      .initial = {2, -1},
                      .max_step_deg = {4, 4},
                      .play_deg = {0.4, 0.2}});
  belief.Expose(1);
  belief.Resolve(Measured(0, 0), kLens);  // the output at the initial angles
  const ServoTargets up = belief.ShaftCommand({3, 0});
  EXPECT_DOUBLE_EQ(up.pan_deg, 3.2);
  EXPECT_DOUBLE_EQ(up.tilt_deg, 0.1);
  const ServoTargets down = belief.ShaftCommand({1, -2});
  EXPECT_DOUBLE_EQ(down.pan_deg, 0.8);
  EXPECT_DOUBLE_EQ(down.tilt_deg, -2.1);
  const ServoTargets held = belief.ShaftCommand({2, -1});  // the shaft stays where it is
  EXPECT_DOUBLE_EQ(held.pan_deg, 2);
  EXPECT_DOUBLE_EQ(held.tilt_deg, -1);
  ServoBelief without_play({.min_delay_frames = 1, .max_delay_frames = 1, .initial = {2, -1}});
  without_play.Expose(1);
  without_play.Resolve(Measured(0, 0), kLens);
  EXPECT_DOUBLE_EQ(without_play.ShaftCommand({3, 0}).pan_deg, 3);
}

TEST(ServoBeliefTest, RefusesAPlayThatIsNegativeOrBeyondABrokenServos) {
  EXPECT_THROW(ServoBelief({.min_delay_frames = 2,
                            .max_delay_frames = 2,
                            .initial = {},
                            .max_step_deg = {4, 4},
                            .play_deg = {-0.1, 0}}),
               std::invalid_argument);
  EXPECT_THROW(ServoBelief({.min_delay_frames = 2,
                            .max_delay_frames = 2,
                            .initial = {},
                            .max_step_deg = {4, 4},
                            .play_deg = {0, 11}}),
               std::invalid_argument);
}

// Remembers the input of its last Update; holds the servos where they are.
class RecordingController final : public Controller {
 public:
  ServoTargets Update(const ControlInput& input, const ServoTargets& current) override {
    last_input = input;
    return current;
  }
  void Reset() override {}
  std::string name() const override { return "recording"; }
  void SetCalibration(const LensCalibration& /*calibration*/) override {}
  void SetGains(const ControllerGains& /*gains*/) override {}

  ControlInput last_input;
};

// The scene of FindsTheCalibrationScale… seen through the controller wrapper: the scale the
// belief found reaches the wrapped controller as its calibration hint, the stored calibration
// ÷ that scale — here near the true deg/px, not the stored one ×1.3.
TEST(ServoBeliefControllerTest, HandsTheControllerTheCalibrationItsViewsAgreeWith) {
  SimulatedServo servo(JitteryServo());
  auto belief = std::make_shared<ServoBelief>(
      ServoBeliefOptions{.min_delay_frames = 2, .max_delay_frames = 3, .initial = {0, 0}});
  const LensCalibration off{1.3 * kLens.pan_deg_per_px, 1.3 * kLens.tilt_deg_per_px};
  auto recording = std::make_unique<RecordingController>();
  const RecordingController* seen = recording.get();
  ServoBeliefController controller(std::move(recording), belief, off);
  for (int t = 0; t < 200; ++t) {
    if (t > 0) servo.Step();
    const double dx =
        -(100 * std::sin(2 * std::numbers::pi * t / 40) + servo.angle() / kLens.pan_deg_per_px);
    belief->Expose(t);
    controller.Update(Measured(dx, 0), {});
    const double command =
        -1.3 * 100 * std::sin(2 * std::numbers::pi * (t + 2.5) / 40) * kLens.pan_deg_per_px;
    servo.Command(command);
    belief->Sent(t, {command, 0});
  }
  EXPECT_NEAR(seen->last_input.pan_deg_per_px_hint, kLens.pan_deg_per_px,
              0.08 * kLens.pan_deg_per_px);
  // Tilt never moved, so its views tell no scale: it takes pan's (one lens), near the truth.
  EXPECT_NEAR(seen->last_input.tilt_deg_per_px_hint, kLens.tilt_deg_per_px,
              0.08 * kLens.tilt_deg_per_px);
}

TEST(ServoBeliefTest, RefusesAnEmptyDelayRange) {
  EXPECT_THROW(ServoBelief({.min_delay_frames = 3, .max_delay_frames = 2, .initial = {}}),
               std::invalid_argument);
  EXPECT_THROW(ServoBelief({.min_delay_frames = 0, .max_delay_frames = 2, .initial = {}}),
               std::invalid_argument);
}

TEST(ServoBeliefControllerTest, HandsTheControllerTheBeliefNotTheCallersGuess) {
  auto belief = std::make_shared<ServoBelief>(
      ServoBeliefOptions{.min_delay_frames = 2, .max_delay_frames = 2, .initial = {0, 0}});
  ServoBeliefController controller(
      std::make_unique<ProportionalController>(ControllerGains{}, kLens), belief, kLens);
  belief->Sent(0, {1.5, -2});
  belief->Expose(2);
  const ServoTargets target = controller.Update(Measured(0, 0), {99, 99});
  EXPECT_DOUBLE_EQ(target.pan_deg, 1.5);
  EXPECT_DOUBLE_EQ(target.tilt_deg, -2);
  EXPECT_EQ(controller.name(), "p");
}

}  // namespace
}  // namespace kapfix
