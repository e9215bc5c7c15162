// Writes the seed files of the fuzzers' kept corpus (tests/fuzz/README.md): for each fuzzer, a
// valid input of every kind ("valid_<kind>", accepted) and inputs that must be refused
// ("bad_<what>"). Deterministic (fixed times), so writing them again changes no file.
// Usage: kapfix_fuzz_seed_writer <corpus-dir>   (normally tests/fuzz/corpus)

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "kapfix/v1/calibration.pb.h"
#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/heartbeat.pb.h"
#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/photo.pb.h"
#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/state.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "kapfix/v1/video.pb.h"
#include "link/envelope.hpp"
#include "tests/fuzz/fuzz_entry_points.hpp"

namespace {

using kapfix::v1::Command;

constexpr std::int64_t kTimeUs = 1'700'000'000'000'000;  // [µs since epoch] a fixed time

// A header as Stamp() fills it, at a fixed time.
void FillHeader(kapfix::v1::Header* header, std::uint64_t sequence) {
  header->set_protocol_version(kapfix::v1::kProtocolVersion);
  header->set_agent_id("kapfix-agent");
  header->set_sequence(sequence);
  header->set_capture_time_us(kTimeUs);
  header->set_send_time_us(kTimeUs);
}

class CorpusFolder {
 public:
  explicit CorpusFolder(std::filesystem::path folder) : folder_(std::move(folder)) {
    std::filesystem::create_directories(folder_);
  }

  void Write(const std::string& name, std::string_view bytes) {
    std::ofstream out(folder_ / name, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + (folder_ / name).string());
    ++written_;
  }

  int written() const { return written_; }

 private:
  std::filesystem::path folder_;
  int written_ = 0;
};

// A stream input: the topic byte, then the payload.
std::string StreamInput(std::string_view topic, std::string_view payload) {
  return std::string(1, static_cast<char>(kapfix::fuzz::TopicByte(topic))) + std::string(payload);
}

kapfix::v1::Telemetry SampleTelemetry() {
  kapfix::v1::Telemetry telemetry;
  FillHeader(telemetry.mutable_header(), 1);
  telemetry.set_frame_number(1234);
  telemetry.set_mode(kapfix::v1::MODE_FIXATE);
  telemetry.mutable_displacement()->set_x_px(-12);
  telemetry.mutable_displacement()->set_y_px(3);
  telemetry.mutable_displacement()->set_x_subpx(0.25F);
  telemetry.set_confidence(0.8F);
  telemetry.set_distance(123456);
  telemetry.set_pan_target_deg(1.5F);
  telemetry.set_tilt_target_deg(-0.5F);
  telemetry.set_pan_angle_deg(1.4F);
  telemetry.set_tilt_angle_deg(-0.4F);
  telemetry.set_fps(29.5F);
  telemetry.set_loop_latency_us(4200);
  telemetry.set_slice(3);
  return telemetry;
}

kapfix::v1::VideoFrame SampleVideoFrame() {
  kapfix::v1::VideoFrame frame;
  FillHeader(frame.mutable_header(), 2);
  frame.set_frame_number(1234);
  std::string jpeg = "\xff\xd8\xff\xe0";  // a JPEG's first bytes; the codec never looks inside
  jpeg.append(96, '\x11');
  jpeg += "\xff\xd9";
  frame.set_jpeg(jpeg);
  frame.set_width_px(320);
  frame.set_height_px(240);
  frame.set_frame_width_px(640);
  frame.set_frame_height_px(480);
  frame.mutable_overlay()->set_slice_count(9);
  frame.mutable_overlay()->set_chosen_slice(3);
  frame.mutable_overlay()->mutable_reference_patch()->set_x(270);
  frame.mutable_overlay()->mutable_reference_patch()->set_width(100);
  frame.mutable_overlay()->mutable_reference_patch()->set_height(100);
  frame.mutable_overlay()->set_has_match(true);
  return frame;
}

kapfix::v1::SliceReport SampleSliceReport() {
  kapfix::v1::SliceReport report;
  FillHeader(report.mutable_header(), 3);
  for (std::uint32_t i = 1; i <= 3; ++i) {
    kapfix::v1::SliceScore* slice = report.add_slices();
    slice->set_index(i);
    slice->set_dc(10 + i);
    slice->set_fft(2.5 * i);
    slice->set_single_shot(0.1F * static_cast<float>(i));
    for (int k = 0; k < 4; ++k) slice->add_graph_px(0.5F * static_cast<float>(k) - 1.0F);
    slice->set_rank(i);
  }
  report.set_recommended_slice(1);
  report.set_progress_done(100);
  report.set_progress_total(100);
  report.set_finished(true);
  report.set_score(kapfix::v1::SLICE_SCORE_KIND_DC);
  report.set_strategy("h23");
  return report;
}

kapfix::v1::PssReport SamplePssReport() {
  kapfix::v1::PssReport report;
  FillHeader(report.mutable_header(), 4);
  for (std::uint32_t side : {50U, 100U, 150U}) {
    kapfix::v1::PatchSizeScore* candidate = report.add_candidates();
    candidate->set_patch_size_px(side);
    candidate->set_dc(side / 10);
    candidate->add_graph_px(1.0F);
    candidate->add_graph_px(-1.0F);
  }
  report.set_recommended_patch_size_px(100);
  report.set_finished(true);
  return report;
}

kapfix::v1::CalibrationReport SampleCalibration() {
  kapfix::v1::CalibrationReport report;
  FillHeader(report.mutable_header(), 5);
  report.set_lens_profile("6mm");
  report.mutable_pan()->set_units_per_px_median(0.05);
  report.mutable_pan()->set_units_per_px_fit(0.051);
  report.mutable_pan()->set_samples(21);
  report.mutable_pan()->set_valid(true);
  report.set_progress_done(105);
  report.set_progress_total(105);
  report.set_finished(true);
  return report;
}

kapfix::v1::Photo SamplePhotoChunk() {
  kapfix::v1::Photo photo;
  FillHeader(photo.mutable_header(), 6);
  photo.mutable_metadata()->set_file_name("photo-0001.png");
  photo.mutable_metadata()->set_capture_time_us(kTimeUs);
  photo.mutable_metadata()->set_slice(3);
  photo.mutable_metadata()->set_width_px(640);
  photo.mutable_metadata()->set_height_px(480);
  photo.mutable_metadata()->set_format("png");
  photo.set_data(std::string(64, '\x42'));
  photo.set_offset_bytes(128);
  photo.set_total_bytes(4096);
  return photo;
}

kapfix::v1::Log SampleLog() {
  kapfix::v1::Log log;
  FillHeader(log.mutable_header(), 7);
  log.set_level(kapfix::v1::LOG_LEVEL_WARN);
  log.set_text("camera reopened after 2 s");
  log.set_logger("capture");
  return log;
}

kapfix::v1::Heartbeat SampleHeartbeat() {
  kapfix::v1::Heartbeat heartbeat;
  FillHeader(heartbeat.mutable_header(), 8);
  heartbeat.set_echoed_send_time_us(kTimeUs - 1000);
  heartbeat.set_echo_hold_us(150);
  heartbeat.set_interval_ms(500);
  heartbeat.set_echoed_sequence(41);
  return heartbeat;
}

kapfix::v1::AgentState SampleState() {
  kapfix::v1::AgentState state;
  FillHeader(state.mutable_header(), 9);
  state.set_mode(kapfix::v1::MODE_IDLE);
  state.mutable_gains()->set_controller(kapfix::v1::CONTROLLER_KIND_PID);
  state.mutable_gains()->set_p(0.8F);
  state.mutable_search()->set_strategy("h23");
  state.mutable_search()->set_slice_count(9);
  state.mutable_search()->set_patch_size_px(100);
  state.set_slice(3);
  state.mutable_lens()->set_name("6mm");
  state.set_frame_width_px(640);
  state.set_frame_height_px(480);
  state.set_simulated(true);
  state.set_agent_version("0.1.0");
  return state;
}

// A command with its header only; each seed adds its command, in range for the fake
// AgentControl's state (640×480 frame, 9 slices) unless it is a bad one.
Command SampleCommand(std::uint64_t sequence) {
  Command command;
  FillHeader(command.mutable_header(), sequence);
  return command;
}

void WriteStreamSeeds(CorpusFolder& folder) {
  const auto write = [&](const google::protobuf::Message& message) {
    const kapfix::link::Envelope envelope = kapfix::link::Encode(message);
    folder.Write("valid_" + envelope.topic, StreamInput(envelope.topic, envelope.payload));
  };
  write(SampleTelemetry());
  write(SampleVideoFrame());
  write(SampleSliceReport());
  write(SamplePssReport());
  write(SampleCalibration());
  write(SamplePhotoChunk());
  write(SampleLog());
  write(SampleHeartbeat());
  Command command = SampleCommand(10);
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  write(command);
  kapfix::v1::Reply reply;
  FillHeader(reply.mutable_header(), 11);
  reply.set_ok(true);
  reply.set_command_sequence(10);
  *reply.mutable_state() = SampleState();
  write(reply);
  write(SampleState());

  kapfix::v1::Telemetry telemetry = SampleTelemetry();
  telemetry.mutable_header()->set_protocol_version(kapfix::v1::kProtocolVersion + 1);
  folder.Write("bad_wrong_version", StreamInput("telemetry", telemetry.SerializeAsString()));
  telemetry = SampleTelemetry();
  telemetry.clear_header();
  folder.Write("bad_no_header", StreamInput("telemetry", telemetry.SerializeAsString()));
  folder.Write("bad_empty_payload", StreamInput("heartbeat", ""));
  const std::string video = SampleVideoFrame().SerializeAsString();
  folder.Write("bad_truncated", StreamInput("video", video.substr(0, video.size() - 5)));
  // A length-delimited field (number 20) that claims more bytes than follow.
  folder.Write(
      "bad_length_beyond_end",
      StreamInput("telemetry", SampleTelemetry().SerializeAsString() + "\xa2\x01\x7f" + "abc"));
  folder.Write("bad_unknown_topic", StreamInput("no-such-topic", SampleLog().SerializeAsString()));
  // proto3 strings must be UTF-8: the station refuses the message rather than show garbage.
  kapfix::v1::Log log = SampleLog();
  log.set_text("\xff\xfe not UTF-8");
  folder.Write("bad_invalid_utf8", StreamInput("log", log.SerializeAsString()));
}

// Every search setting at a valid value.
Command SearchCommand(std::uint64_t sequence) {
  Command command = SampleCommand(sequence);
  auto* search = command.mutable_set_search();
  search->set_strategy("h23");
  search->set_sampling(kapfix::v1::SAMPLING_RANDOM);
  search->set_random_fraction(0.3F);
  search->set_patch_size_px(100);
  search->set_slice_count(9);
  search->set_axis(kapfix::v1::AXIS_X);
  search->set_search_range_px(100);
  search->set_subpixel(true);
  search->set_channel(kapfix::v1::CHANNEL_GREEN);
  search->set_slice_score(kapfix::v1::SLICE_SCORE_KIND_DC_HYSTERESIS);
  search->set_dc_hysteresis_px(2.0F);
  return command;
}

// Commands the agent accepts, one per kind.
void WriteValidCommandSeeds(CorpusFolder& folder, std::uint64_t* sequence) {
  const auto write = [&](const std::string& name, const Command& command) {
    folder.Write(name, command.SerializeAsString());
  };
  Command command = SampleCommand(++*sequence);
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  command.mutable_set_mode()->set_deadline_frames(600);
  command.mutable_set_mode()->set_deadline_s(30.0F);
  write("valid_set_mode", command);

  command = SampleCommand(++*sequence);
  auto* gains = command.mutable_set_gains();
  gains->set_controller(kapfix::v1::CONTROLLER_KIND_PID);
  gains->set_p(0.8F);
  gains->set_i(0.1F);
  gains->set_d(0.05F);
  gains->set_dead_band_px(1.0F);
  gains->set_rate_limit_deg_per_s(90.0F);
  write("valid_set_gains", command);

  write("valid_set_search", SearchCommand(++*sequence));

  command = SampleCommand(++*sequence);
  command.set_select_slice(3);
  write("valid_select_slice", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_camera()->set_gain_db(6.0F);
  command.mutable_set_camera()->set_exposure_us(5000.0F);
  command.mutable_set_camera()->set_auto_exposure(false);
  write("valid_set_camera", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_lens()->set_name("6mm");
  command.mutable_set_lens()->set_focal_length_mm(6.0F);
  command.mutable_set_lens()->set_pixel_pitch_um(3.75F);
  write("valid_set_lens", command);

  command = SampleCommand(++*sequence);
  command.mutable_take_photo()->set_note("north shore, 40 m line");
  write("valid_take_photo", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_photo()->set_interval_s(10.0F);
  write("valid_set_photo_interval_s", command);

  command = SampleCommand(++*sequence);
  command.mutable_request_state()->set_resend_photos_since_us(kTimeUs - 60'000'000);
  command.mutable_request_state()->set_resend_slice_report(true);
  write("valid_request_state", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_video()->set_fps(15.0F);
  command.mutable_set_video()->set_jpeg_quality(80);
  command.mutable_set_video()->set_scale(0.5F);
  write("valid_set_video", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_photo()->set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  command.mutable_set_photo()->set_window_s(2.0F);
  command.mutable_set_photo()->set_exposure_ms(10.0F);
  write("valid_set_photo", command);

  // An empty agent id addresses whichever agent answers.
  command = SampleCommand(++*sequence);
  command.mutable_header()->clear_agent_id();
  command.set_select_slice(1);
  write("valid_to_any_agent", command);
}

// Frames the agent refuses before it reads the command: version, header, size.
void WriteMalformedCommandSeeds(CorpusFolder& folder, std::uint64_t* sequence) {
  const auto write = [&](const std::string& name, const Command& command) {
    folder.Write(name, command.SerializeAsString());
  };
  Command command = SampleCommand(++*sequence);
  command.mutable_header()->set_protocol_version(kapfix::v1::kProtocolVersion + 1);
  command.set_select_slice(3);
  write("bad_wrong_version", command);

  command = SampleCommand(++*sequence);
  command.clear_header();
  command.set_select_slice(3);
  write("bad_no_header", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_gains()->set_p(0.8F);
  const std::string gains_bytes = command.SerializeAsString();
  folder.Write("bad_truncated", gains_bytes.substr(0, gains_bytes.size() - 2));

  // One byte over the limit; the note alone would be refused later, the size check must come
  // first (the agent does not parse what it will not keep).
  command = SampleCommand(++*sequence);
  command.mutable_take_photo()->set_note(std::string(kapfix::v1::kMaxCommandBytes, 'n'));
  std::string oversized = command.SerializeAsString();
  oversized.resize(kapfix::v1::kMaxCommandBytes + 1);
  folder.Write("bad_oversized", oversized);
}

// Commands the agent refuses for their values: out of range, not finite, unknown.
void WriteRefusedValueCommandSeeds(CorpusFolder& folder, std::uint64_t* sequence) {
  const auto write = [&](const std::string& name, const Command& command) {
    folder.Write(name, command.SerializeAsString());
  };
  Command command = SampleCommand(++*sequence);
  command.mutable_set_gains()->set_p(std::numeric_limits<float>::quiet_NaN());
  write("bad_nan_gain", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_camera()->set_exposure_us(std::numeric_limits<float>::infinity());
  write("bad_infinite_exposure", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_gains()->set_rate_limit_deg_per_s(0.0F);
  write("bad_zero_rate_limit", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_mode()->set_mode(static_cast<kapfix::v1::Mode>(42));
  write("bad_unknown_mode", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_UNSPECIFIED);
  write("bad_unspecified_mode", command);

  command = SampleCommand(++*sequence);
  command.set_select_slice(10);  // the fake has 9 slices
  write("bad_slice_out_of_range", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_search()->set_patch_size_px(1000);  // the fake's frame is 640×480
  write("bad_patch_larger_than_frame", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_search()->set_strategy("h99");
  write("bad_unknown_strategy", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_lens()->set_name("../../etc/passwd");
  write("bad_lens_name_path", command);

  command = SampleCommand(++*sequence);
  command.mutable_set_photo()->set_interval_s(0.1F);
  write("bad_photo_interval_too_short", command);

  command = SampleCommand(++*sequence);
  command.mutable_request_state()->set_resend_photos_since_us(-1);
  write("bad_negative_resend_time", command);
}

// Commands not for this agent, not numbered, empty, from a newer station, or not UTF-8.
void WriteMisaddressedCommandSeeds(CorpusFolder& folder, std::uint64_t* sequence) {
  const auto write = [&](const std::string& name, const Command& command) {
    folder.Write(name, command.SerializeAsString());
  };
  Command command = SampleCommand(++*sequence);
  command.mutable_header()->set_agent_id("someone-else");
  command.set_select_slice(3);
  write("bad_other_agent", command);

  command = SampleCommand(0);
  command.set_select_slice(3);
  write("bad_sequence_zero", command);

  write("bad_no_command", SampleCommand(++*sequence));

  // Field 99 (varint 1): a command from a newer station that this agent does not know.
  folder.Write("bad_unknown_command_field",
               SampleCommand(++*sequence).SerializeAsString() + "\x98\x06\x01");

  command = SampleCommand(++*sequence);
  command.mutable_header()->set_agent_id("\xff\xfe");
  command.set_select_slice(3);
  write("bad_invalid_utf8_agent_id", command);
}

void WriteCommandSeeds(CorpusFolder& folder) {
  std::uint64_t sequence = 100;
  WriteValidCommandSeeds(folder, &sequence);
  WriteMalformedCommandSeeds(folder, &sequence);
  WriteRefusedValueCommandSeeds(folder, &sequence);
  WriteMisaddressedCommandSeeds(folder, &sequence);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <corpus-dir>\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path corpus = argv[1];
    CorpusFolder streams(corpus / "stream_message_decoding_fuzzer");
    WriteStreamSeeds(streams);
    CorpusFolder commands(corpus / "command_handling_fuzzer");
    WriteCommandSeeds(commands);
    std::printf("seed corpus: %d stream and %d command seeds in %s\n", streams.written(),
                commands.written(), corpus.c_str());
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
  return 0;
}
