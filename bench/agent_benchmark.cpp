// kapfix-bench-agent: the agent's own throughput on one core (issue 3: ≥ 200 frames/s of
// 640×480 with telemetry and a 10 fps video downlink running).
//
// The frames are a kite's free swing over a scene, rendered before the clock starts, so that
// the figure is the agent's work — fixation (match + control), telemetry publishing, the
// video downlink's JPEG encoding — and not the simulator's rendering, which a real camera does
// not cost. The process is pinned to one CPU; the link publishes to a real subscriber on
// loopback. Figures: wall-clock fps, fps per CPU-second (robust on a shared machine), loop
// latency, and the ratio against cv::matchTemplate on the same frames (a peer measured in the
// same run).
#include <sched.h>
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <thread>
#include <zmq.hpp>

#include "agent/capture/fake_frame_source.hpp"
#include "agent/commands/state_keeper.hpp"
#include "agent/config/agent_config.hpp"
#include "agent/downlink/telemetry_publisher.hpp"
#include "agent/downlink/video_downlink.hpp"
#include "agent/modes/mode_runner.hpp"
#include "agent/pipeline/pipeline.hpp"
#include "agent/pipeline/telemetry_recorder.hpp"
#include "agent/server/stream_publisher.hpp"
#include "agent/servo/fake_servo_driver.hpp"
#include "agent/servo/limited_servo_driver.hpp"
#include "common/analysis/statistics.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"
#include "common/sim/simulated_platform.hpp"

namespace {

using namespace kapfix;
using namespace kapfix::agent;

double CpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
}

std::vector<cv::Mat> RenderSwing(const std::string& scene_path, int count) {
  const cv::Mat scene = cv::imread(scene_path, cv::IMREAD_COLOR);
  if (scene.empty()) throw std::runtime_error("cannot read scene '" + scene_path + "'");
  SimulatedPlatformOptions options =
      ClosedLoopOptions::ForMotion(SimulatedPlatformOptions::Motion::kKite).platform;
  options.camera.frame_size = {640, 480};
  SimulatedPlatform platform(scene, options);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    frames.push_back(platform.CaptureFrame().image);
    platform.Step();
  }
  return frames;
}

// What a station does with the streams: reads every message.
class DrainingStation {
 public:
  explicit DrainingStation(const std::string& endpoint) : socket_(context_, zmq::socket_type::sub) {
    socket_.set(zmq::sockopt::subscribe, "");
    socket_.set(zmq::sockopt::rcvtimeo, 100);
    socket_.connect(endpoint);
    thread_ = std::thread([this] {
      zmq::message_t message;
      while (!stop_) {
        if (socket_.recv(message, zmq::recv_flags::none)) ++received_;
      }
    });
  }
  ~DrainingStation() {
    stop_ = true;
    thread_.join();
  }
  DrainingStation(const DrainingStation&) = delete;
  DrainingStation& operator=(const DrainingStation&) = delete;
  std::uint64_t received() const { return received_; }

 private:
  zmq::context_t context_{1};
  zmq::socket_t socket_;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> received_{0};
  std::thread thread_;
};

// [ms] per frame of cv::matchTemplate (TM_SQDIFF) of the 100×100 patch over the whole frame.
double MatchTemplateMs(const std::vector<cv::Mat>& frames, int repeats) {
  cv::Mat reference;
  cv::extractChannel(frames.front(), reference, 1);
  const cv::Rect centre((reference.cols - 100) / 2, (reference.rows - 100) / 2, 100, 100);
  const cv::Mat patch = reference(centre).clone();
  cv::Mat plane;
  cv::Mat result;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < repeats; ++i) {
    cv::extractChannel(frames[static_cast<std::size_t>(i) % frames.size()], plane, 1);
    cv::matchTemplate(plane, patch, result, cv::TM_SQDIFF);
  }
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
             .count() /
         repeats;
}

class NullEvents : public ModeEvents {
 public:
  void OnModeChanged(AgentMode /*mode*/, int /*slice*/) override {}
  void OnSliceReport(const kapfix::v1::SliceReport& /*report*/) override {}
  void OnPssReport(const kapfix::v1::PssReport& /*report*/) override {}
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& /*report*/,
                           const std::optional<LensCalibration>& /*applied*/) override {}
  void OnFreeSwingRecorded(const std::string& /*path*/, const std::string& /*error*/) override {}
};

void PinToCpu(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0) std::perror("sched_setaffinity");
}

void PrintFigures(const PipelineStats& stats, double cpu_s, const TelemetryRecorder& recorder,
                  double match_template_ms, const StreamPublisher::Counters& counters,
                  const VideoDownlink& video, const DrainingStation& station) {
  std::vector<double> latency;
  for (const TelemetryRecord& r : recorder.records()) latency.push_back(r.loop_latency_ms);
  const double per_frame_ms = 1000.0 * stats.wall_s / static_cast<double>(stats.processed);
  std::printf("frames processed:       %llu in %.2f s (dropped %llu)\n",
              static_cast<unsigned long long>(stats.processed), stats.wall_s,
              static_cast<unsigned long long>(stats.dropped));
  std::printf("fps (wall clock):       %.1f\n",
              static_cast<double>(stats.processed) / stats.wall_s);
  std::printf("fps per CPU-second:     %.1f   (CPU %.2f s, all threads, pinned to one CPU)\n",
              static_cast<double>(stats.processed) / cpu_s, cpu_s);
  std::printf("loop latency p50/p99:   %.3f / %.3f ms\n", Percentile(latency, 50),
              Percentile(latency, 99));
  std::printf(
      "telemetry sent/dropped: %llu / %llu; video sent %llu, dropped %llu; station read %llu\n",
      static_cast<unsigned long long>(counters.telemetry_sent),
      static_cast<unsigned long long>(counters.telemetry_dropped),
      static_cast<unsigned long long>(video.sent()),
      static_cast<unsigned long long>(video.dropped()),
      static_cast<unsigned long long>(station.received()));
  std::printf("per frame: agent %.3f ms, cv::matchTemplate alone %.3f ms (ratio %.1fx)\n",
              per_frame_ms, match_template_ms, match_template_ms / per_frame_ms);
}

int Run(int argc, char** argv) {
  CLI::App app{"kapfix-bench-agent: the agent's frames per second on one core"};
  std::uint64_t frames = 3000;
  double camera_fps = 200;
  double video_fps = 10;
  int cpu = 0;
  std::string strategy = "pyr";
  std::string scene = std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg";
  app.add_option("--frames", frames, "frames to process")->check(CLI::PositiveNumber);
  app.add_option("--camera-fps", camera_fps, "frame times as from a camera this fast")
      ->check(CLI::PositiveNumber);
  app.add_option("--video-fps", video_fps, "video downlink rate [frames/s of camera time]");
  app.add_option("--cpu", cpu, "CPU to pin the process to; -1 = no pinning");
  app.add_option("--strategy", strategy, "search strategy");
  app.add_option("--scene", scene, "scene photo");
  CLI11_PARSE(app, argc, argv);

  if (cpu >= 0) PinToCpu(cpu);
  std::printf("rendering 300 frames of the kite's swing over %s …\n", scene.c_str());
  const std::vector<cv::Mat> swing = RenderSwing(scene, 300);

  AgentConfig config;
  config.search.strategy = strategy;
  config.search.axis = SearchAxis::kBoth;
  config.video.set_fps(static_cast<float>(video_fps));
  StreamPublisherOptions publisher_options;
  publisher_options.bind_endpoint = "tcp://127.0.0.1:*";
  StreamPublisher publisher(publisher_options);
  const std::string endpoint = publisher.Start();
  DrainingStation station(endpoint);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the subscription settles

  FakeFrameSource source(swing, static_cast<std::int64_t>(1e6 / camera_fps));
  LimitedServoDriver servos(std::make_unique<FakeServoDriver>(), config.servo.pan.limits,
                            config.servo.tilt.limits, SteadyClockNowUs);
  std::string error;
  if (!source.Open(&error) || !servos.Open(&error)) throw std::runtime_error(error);
  VideoDownlink video(publisher, config.video);
  TelemetryPublisher telemetry(publisher, [&video] { return video.dropped(); });
  TelemetryRecorder recorder;
  NullEvents events;
  ModeRunnerOptions modes;
  modes.frame_period_s = 1.0 / camera_fps;
  ModeRunner runner(config, modes, events);
  PipelineOptions options;
  options.frames = frames;
  options.lock_step = true;  // the camera never outruns the loop: no frame is grabbed for nothing
  Pipeline pipeline(source, servos, runner, {&telemetry, &video, &recorder}, options);

  std::printf(
      "flying %llu frames (strategy %s, telemetry on, video %.0f fps of camera time, "
      "camera %.0f fps)…\n",
      static_cast<unsigned long long>(frames), strategy.c_str(), video_fps, camera_fps);
  const double cpu_start = CpuSeconds();
  const PipelineStats stats = pipeline.Run();
  const double cpu_s = CpuSeconds() - cpu_start;
  const double match_template_ms = MatchTemplateMs(swing, 100);  // the peer, on the same frames
  PrintFigures(stats, cpu_s, recorder, match_template_ms, publisher.counters(), video, station);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kapfix-bench-agent: %s\n", e.what());
    return 1;
  }
}
