// Writes a synthetic session file (link/session_recorder.hpp) for the station's documentation
// screenshot when no agent serves the link: a kite's free swing over an aerial photo (opencv-doc's
// aero3.jpg), an SSP run whose slice graphs and scores are computed from that swing, then fixation
// on the recommended slice. Everything is made up here — it shows the views, not the method's
// results; deploy/station-screenshot.sh takes the real picture against an agent.
//
// Usage: kapfix_station_demo_session OUT.kfxrec [SCENE.jpg]
#include <QBuffer>
#include <QCoreApplication>
#include <QGuiApplication>
#include <QImage>
#include <QPainter>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/state.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"
#include "link/envelope.hpp"
#include "link/session_recorder.hpp"

namespace {

constexpr int kFps = 25;      // [fps]
constexpr int kFrameW = 480;  // [px] camera frame
constexpr int kFrameH = 360;  // [px]
constexpr unsigned kSlices = 9;
constexpr unsigned kChosen = 3;
constexpr int kPatch = 100;                               // [px]
constexpr double kSwingPx = 60;                           // [px] amplitude of the free swing
constexpr double kPeriodS = 2.4;                          // [s]
constexpr int kIdleFrames = kFps;                         // 1 s idle
constexpr int kSspFrames = 8 * kFps;                      // 8 s of free swing
constexpr int kFixateFrames = 6 * kFps;                   // 6 s of fixation
constexpr std::int64_t kStartUs = 1'700'000'000'000'000;  // [µs since epoch] any fixed time

class Writer {
 public:
  explicit Writer(const std::string& path) : recorder_(path) {}

  template <typename Message>
  void Put(Message message, std::int64_t time_us) {
    kapfix::v1::Stamp(message.mutable_header(), "demo-agent", ++sequence_);
    message.mutable_header()->set_capture_time_us(time_us);
    message.mutable_header()->set_send_time_us(time_us);
    const kapfix::link::Envelope envelope = kapfix::link::Encode(message);
    recorder_.Write(envelope.topic, envelope.payload, time_us);
  }
  void Flush() { recorder_.Flush(); }

 private:
  kapfix::link::SessionRecorder recorder_;
  std::uint64_t sequence_ = 0;
};

unsigned DirectionChanges(const std::vector<float>& graph) {
  unsigned changes = 0;
  int last_sign = 0;
  for (std::size_t t = 1; t < graph.size(); ++t) {
    const float step = graph[t] - graph[t - 1];
    const int sign = step > 0 ? 1 : (step < 0 ? -1 : 0);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) ++changes;
    last_sign = sign;
  }
  return changes;
}

double FftScore(const std::vector<float>& graph) {
  const std::size_t n = graph.size();
  double sum = 0;
  for (std::size_t k = 1; k <= n / 2; ++k) {
    std::complex<double> bin;
    for (std::size_t t = 0; t < n; ++t) {
      bin += static_cast<double>(graph[t]) *
             std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(k * t) /
                                 static_cast<double>(n));
    }
    sum += std::abs(bin);
  }
  return sum;
}

double Swing(int frame) {  // [px] where the free swing has moved the view
  const double t = static_cast<double>(frame) / kFps;
  return kSwingPx * std::sin(2 * std::numbers::pi * t / kPeriodS) * std::exp(-t / 30.0);
}

kapfix::v1::Rect Rect(int x, int y, int w, int h) {
  kapfix::v1::Rect rect;
  rect.set_x(x);
  rect.set_y(y);
  rect.set_width(w);
  rect.set_height(h);
  return rect;
}

// Where one frame looks [px]: the swing plus what the servos took out of it.
struct View {
  double x = 0;
  double y = 0;
  double servo_px = 0;  // [px] the pan servo's share, fixating only
};

// One draw after another from a fixed seed: the same session every run.
class Noise {
 public:
  double operator()() { return normal_(random_); }

 private:
  std::mt19937 random_{7};
  std::normal_distribution<double> normal_{0.0, 1.0};
};

constexpr std::int64_t TimeOf(int frame) {
  return kStartUs + static_cast<std::int64_t>(frame) * 1'000'000 / kFps;
}

constexpr int kPatchY = static_cast<int>((kChosen - 0.5) * kFrameH / kSlices) - kPatch / 2;
constexpr int kPatchX = (kFrameW - kPatch) / 2;

// The scene the frames are cut from, twice the frame's size; a plain pattern stands in when
// the photo cannot be read.
QImage LoadScene(int argc, char** argv) {
  QImage scene(argc > 2 ? QString::fromLocal8Bit(argv[2])
                        : QStringLiteral("/usr/share/doc/opencv-doc/examples/data/aero3.jpg"));
  if (scene.isNull()) {
    scene = QImage(960, 720, QImage::Format_RGB32);
    QPainter painter(&scene);
    for (int i = 0; i < 400; ++i) {
      painter.fillRect((i * 97) % 960, (i * 61) % 720, 40 + i % 50, 30 + i % 40,
                       QColor::fromHsv((i * 37) % 360, 90, 120 + i % 100));
    }
  }
  return scene.scaled(kFrameW * 2, kFrameH * 2, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
}

kapfix::v1::AgentState DemoState() {
  kapfix::v1::AgentState state;
  state.set_mode(kapfix::v1::MODE_IDLE);
  state.set_frame_width_px(kFrameW);
  state.set_frame_height_px(kFrameH);
  state.set_simulated(true);
  state.set_agent_version("demo");
  state.mutable_gains()->set_controller(kapfix::v1::CONTROLLER_KIND_PREDICTIVE);
  state.mutable_gains()->set_p(0.8F);
  state.mutable_gains()->set_i(0.2F);
  state.mutable_gains()->set_d(0.02F);
  state.mutable_gains()->set_dead_band_px(1.0F);
  state.mutable_gains()->set_rate_limit_deg_per_s(120.0F);
  auto* search = state.mutable_search();
  search->set_strategy("h23");
  search->set_sampling(kapfix::v1::SAMPLING_STATIC);
  search->set_random_fraction(0.1F);
  search->set_patch_size_px(kPatch);
  search->set_slice_count(kSlices);
  search->set_axis(kapfix::v1::AXIS_X);
  search->set_search_range_px(100);
  search->set_channel(kapfix::v1::CHANNEL_GREEN);
  search->set_slice_score(kapfix::v1::SLICE_SCORE_KIND_DC);
  search->set_dc_hysteresis_px(1.0F);
  state.mutable_camera()->set_gain_db(6.0F);
  state.mutable_camera()->set_exposure_us(4000.0F);
  state.mutable_lens()->set_name("3.5mm");
  state.mutable_lens()->set_focal_length_mm(3.5F);
  state.mutable_lens()->set_pixel_pitch_um(4.8F);
  state.mutable_video()->set_fps(25.0F);
  state.mutable_video()->set_jpeg_quality(80);
  state.mutable_video()->set_scale(1.0F);
  return state;
}

kapfix::v1::Telemetry DemoTelemetry(int frame, kapfix::v1::Mode mode, const View& view,
                                    Noise& noise) {
  const bool fixate = mode == kapfix::v1::MODE_FIXATE;
  kapfix::v1::Telemetry telemetry;
  telemetry.set_frame_number(static_cast<std::uint64_t>(frame));
  telemetry.set_mode(mode);
  telemetry.mutable_displacement()->set_x_px(static_cast<int>(std::lround(view.x)));
  telemetry.mutable_displacement()->set_y_px(static_cast<int>(std::lround(view.y)));
  telemetry.set_confidence(static_cast<float>(std::clamp(0.82 + 0.06 * noise(), 0.0, 1.0)));
  telemetry.set_distance(static_cast<std::int64_t>(180'000 + 25'000 * std::abs(noise())));
  const double pan = fixate ? view.servo_px * 0.08 : 0.0;  // [deg] 0.08 deg/px
  telemetry.set_pan_target_deg(static_cast<float>(pan + 0.2));
  telemetry.set_pan_angle_deg(static_cast<float>(pan));
  telemetry.set_tilt_target_deg(static_cast<float>(-0.1 * view.y));
  telemetry.set_tilt_angle_deg(static_cast<float>(-0.1 * view.y * 0.9));
  telemetry.set_fps(static_cast<float>(kFps - 0.4 + 0.3 * noise()));
  telemetry.set_loop_latency_us(8500);
  telemetry.set_slice(fixate ? kChosen : 0);
  return telemetry;
}

// The frame cut from the scene where the view is, as JPEG, with the slice overlay.
kapfix::v1::VideoFrame DemoVideoFrame(const QImage& scene, int frame, bool fixate,
                                      const View& view) {
  const int x = static_cast<int>(std::lround(view.x));
  const int y = static_cast<int>(std::lround(view.y));
  QImage picture = scene.copy(kFrameW / 2 + x, kFrameH / 2 + y, kFrameW, kFrameH);
  QByteArray jpeg;
  QBuffer buffer(&jpeg);
  buffer.open(QIODevice::WriteOnly);
  picture.save(&buffer, "JPEG", 80);
  kapfix::v1::VideoFrame video;
  video.set_frame_number(static_cast<std::uint64_t>(frame));
  video.set_jpeg(jpeg.toStdString());
  video.set_width_px(kFrameW);
  video.set_height_px(kFrameH);
  video.set_frame_width_px(kFrameW);
  video.set_frame_height_px(kFrameH);
  auto* overlay = video.mutable_overlay();
  overlay->set_slice_count(kSlices);
  if (fixate) {
    overlay->set_chosen_slice(kChosen);
    *overlay->mutable_reference_patch() = Rect(kPatchX, kPatchY, kPatch, kPatch);
    *overlay->mutable_current_match() = Rect(kPatchX - x, kPatchY - y, kPatch, kPatch);
    overlay->set_has_match(true);
  }
  return video;
}

// The SSP's progress after `t` + 1 frames; the last one ranks the slices by their direction
// changes and recommends the calmest.
kapfix::v1::SliceReport DemoSliceReport(int t, const std::vector<std::vector<float>>& graphs,
                                        const std::vector<double>& slice_noise) {
  kapfix::v1::SliceReport report;
  report.set_progress_done(static_cast<std::uint32_t>(t + 1));
  report.set_progress_total(kSspFrames);
  report.set_patch_size_px(kPatch);
  report.set_strategy("h23");
  report.set_score(kapfix::v1::SLICE_SCORE_KIND_DC);
  if (t != kSspFrames - 1) return report;
  std::vector<unsigned> order(kSlices);
  for (unsigned s = 0; s < kSlices; ++s) order[s] = s;
  std::vector<unsigned> dcs(kSlices);
  for (unsigned s = 0; s < kSlices; ++s) dcs[s] = DirectionChanges(graphs[s]);
  std::sort(order.begin(), order.end(), [&](unsigned a, unsigned b) { return dcs[a] < dcs[b]; });
  for (unsigned s = 0; s < kSlices; ++s) {
    auto* score = report.add_slices();
    score->set_index(s + 1);
    score->set_dc(dcs[s]);
    score->set_dc_hysteresis(dcs[s] / 2);
    score->set_fft(FftScore(graphs[s]));
    score->set_single_shot(static_cast<float>(1.0 / (1.0 + slice_noise[s])));
    for (const float v : graphs[s]) score->add_graph_px(v);
    score->set_rank(
        static_cast<std::uint32_t>(std::find(order.begin(), order.end(), s) - order.begin() + 1));
  }
  report.set_recommended_slice(order.front() + 1);
  report.set_finished(true);
  return report;
}

// The operator's commands and the agent's replies: SSP after the idle second, then the
// recommended slice once the SSP has finished.
void PutOperatorCommands(Writer& writer, int frame, std::int64_t now) {
  if (frame == kIdleFrames - 1) {
    kapfix::v1::Command command;
    command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
    command.mutable_set_mode()->set_deadline_frames(kSspFrames);
    writer.Put(command, now + 5000);
    kapfix::v1::Reply reply;
    reply.set_ok(true);
    writer.Put(reply, now + 9000);
  }
  if (frame == kIdleFrames + kSspFrames - 1) {
    kapfix::v1::Command command;
    command.set_select_slice(kChosen);
    writer.Put(command, now + 400'000);
    kapfix::v1::Reply reply;
    reply.set_ok(true);
    writer.Put(reply, now + 405'000);
  }
}

}  // namespace

int main(int argc, char** argv) {
  QGuiApplication app(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s OUT.kfxrec [SCENE.jpg]\n", argv[0]);
    return 2;
  }
  const QImage scene = LoadScene(argc, argv);
  Writer writer(argv[1]);
  Noise noise;
  writer.Put(DemoState(), TimeOf(0));

  // Per slice, how badly it tracks: texture-poor bands (sky-like top, blurred bottom) are
  // noisier; slice 3 is the calmest.
  const std::vector<double> slice_noise = {2.6, 1.4, 0.35, 0.8, 1.1, 1.6, 1.9, 2.3, 3.0};
  std::vector<std::vector<float>> graphs(kSlices);

  const int total = kIdleFrames + kSspFrames + kFixateFrames;
  int frame = 0;
  for (frame = 0; frame < total; ++frame) {
    const bool ssp = frame >= kIdleFrames && frame < kIdleFrames + kSspFrames;
    const bool fixate = frame >= kIdleFrames + kSspFrames;
    const double swing = Swing(frame);
    View view;
    // Fixating, the servos take out most of the swing; what is left is a small error.
    view.servo_px = fixate ? -swing + 1.5 * noise() : 0.0;
    view.x = swing + view.servo_px;
    view.y = 2.0 * std::sin(frame * 0.37) + 0.6 * noise();
    const std::int64_t now = TimeOf(frame);
    const kapfix::v1::Mode mode =
        fixate ? kapfix::v1::MODE_FIXATE : (ssp ? kapfix::v1::MODE_SSP : kapfix::v1::MODE_IDLE);
    writer.Put(DemoTelemetry(frame, mode, view, noise), now);
    writer.Put(DemoVideoFrame(scene, frame, fixate, view), now + 2000);

    if (ssp) {
      const int t = frame - kIdleFrames;
      for (unsigned s = 0; s < kSlices; ++s) {
        const double step = Swing(frame) - Swing(frame - 1);
        graphs[s].push_back(static_cast<float>(std::lround(step + slice_noise[s] * noise())));
      }
      if (t % 10 == 9 || t == kSspFrames - 1) {
        writer.Put(DemoSliceReport(t, graphs, slice_noise), now + 3000);
      }
    }
    PutOperatorCommands(writer, frame, now);
  }
  writer.Flush();
  std::fprintf(stderr, "wrote %d frames to %s\n", frame, argv[1]);
  return 0;
}
