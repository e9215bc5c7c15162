// kapfix-ctl: a headless ground station for scripts and tests (issue 3). One subcommand per
// run; the exit code says what happened (see kExitCodes below and --help).
#include <google/protobuf/util/json_util.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/photo.pb.h"
#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "link/curve_key_file.hpp"
#include "tools/ctl/agent_link_client.hpp"
#include "tools/ctl/message_text.hpp"
#include "tools/ctl/photo_assembler.hpp"
#include "tools/ctl/photo_saving.hpp"
#include "tools/ctl/session_recorder.hpp"
#include "tools/ctl/setting_key.hpp"

namespace {

using kapfix::link::AgentLinkClient;
using kapfix::v1::Command;
using Clock = std::chrono::steady_clock;

enum Exit : int { kOk = 0, kRefused = 1, kBadArguments = 2, kNoAnswer = 3 };

constexpr const char* kExitCodes =
    "Exit codes:\n"
    "  0  ok\n"
    "  1  the agent refused the command (its reason is printed on stderr)\n"
    "  2  bad arguments (unknown key, unreadable value, missing folder, bad key file)\n"
    "  3  no answer within --timeout: the link is down, no agent listens, or it refused\n"
    "     this station's CurveZMQ key (the reason is printed when ZeroMQ tells it)\n";

struct LinkArguments {
  std::string host = "localhost";
  int command_port = 5555;
  int stream_port = 5556;
  int timeout_ms = 3000;
  std::string agent_id;
  std::string key_file;        // this station's secret key file (kapfix-keygen)
  std::string agent_key_file;  // the agent's public key file
  std::optional<kapfix::link::CurveClientKeys> curve;  // read from the two files

  std::chrono::milliseconds timeout() const { return std::chrono::milliseconds(timeout_ms); }
  std::string CommandEndpoint() const {
    return "tcp://" + host + ":" + std::to_string(command_port);
  }
  std::string StreamEndpoint() const { return "tcp://" + host + ":" + std::to_string(stream_port); }
};

std::atomic<bool> g_interrupted{false};

extern "C" void OnInterrupt(int /*signal*/) { g_interrupted.store(true); }

void Error(const std::string& text) { std::cerr << "kapfix-ctl: " << text << std::endl; }

std::unique_ptr<AgentLinkClient> MakeClient(const LinkArguments& link) {
  kapfix::link::AgentLinkClientOptions options;
  options.command_endpoint = link.CommandEndpoint();
  options.stream_endpoint = link.StreamEndpoint();
  options.agent_id = link.agent_id;
  options.curve = link.curve;
  // Link loss is declared after --timeout of silence. Our own heartbeats, echoed by the
  // agent, come three times per timeout so that a short --timeout does not mistake the
  // agent's slower stream heartbeats (1 s) for a lost link.
  options.link_timeout = link.timeout();
  options.heartbeat_interval = std::clamp<std::chrono::milliseconds>(
      link.timeout() / 3, std::chrono::milliseconds(10), options.heartbeat_interval);
  return std::make_unique<AgentLinkClient>(options);
}

// Sends one command and reports the outcome as an exit code; `reply` receives an OK reply.
int Send(AgentLinkClient& client, const LinkArguments& link, Command command,
         kapfix::v1::Reply* reply = nullptr) {
  const auto answer = client.Request(std::move(command), link.timeout());
  if (!answer) {
    const std::string refused = client.Status().handshake_failure;
    Error("no answer from " + link.CommandEndpoint() + " within " +
          std::to_string(link.timeout_ms) + " ms (" +
          (refused.empty() ? std::string("link down or no agent") : refused) + ")");
    return kNoAnswer;
  }
  if (!answer->ok()) {
    Error("agent refused: " + answer->reason() + " [" +
          kapfix::v1::ErrorCode_Name(answer->error()) + "]");
    return kRefused;
  }
  if (reply != nullptr) *reply = *answer;
  return kOk;
}

void PrintLine(const std::string& line) {
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fputc('\n', stdout);
  std::fflush(stdout);
}

// "1.23": seconds with two decimals, for the summary lines.
std::string SecondsText(double seconds) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.2f", seconds);
  return text.data();
}

// True while the agent was heard within --timeout (counting from `since` if never heard).
bool LinkAlive(const AgentLinkClient& client, const LinkArguments& link, Clock::time_point since) {
  if (client.Status().up) return true;
  return Clock::now() - since < link.timeout() && client.Status().last_heard_us == 0;
}

int LinkDown(const AgentLinkClient& client, const LinkArguments& link) {
  const std::string refused = client.Status().handshake_failure;
  Error("no message from the agent at " + link.StreamEndpoint() + " within " +
        std::to_string(link.timeout_ms) + " ms (" +
        (refused.empty() ? std::string("link down or no agent") : refused) + ")");
  return kNoAnswer;
}

// Waits for the stream subscription to be live, so that results published right after the
// command are not lost (ZeroMQ PUB does not keep messages for late subscribers).
bool StreamsReady(AgentLinkClient& client, const LinkArguments& link) {
  return client.WaitForStreams(link.timeout());
}

int RunStatus(const LinkArguments& link, bool json) {
  auto client = MakeClient(link);
  client->Start();
  Command command;
  command.mutable_request_state();
  kapfix::v1::Reply reply;
  const int code = Send(*client, link, std::move(command), &reply);
  if (code != kOk) return code;
  if (json) {
    std::string text;
    google::protobuf::util::JsonPrintOptions options;
    options.add_whitespace = true;
    (void)google::protobuf::util::MessageToJsonString(reply.state(), &text, options);
    std::cout << text;
  } else {
    std::cout << kapfix::ctl::StateText(reply.state());
  }
  std::cout.flush();
  return kOk;
}

struct WatchOptions {
  int count = 0;          // [messages] stop after this many; 0 = no limit
  double duration_s = 0;  // [s] stop after this long; 0 = no limit
  bool summary = false;   // one line at the end instead of a line per message
};

int RunWatch(const LinkArguments& link, const WatchOptions& watch) {
  std::atomic<int> received{0};  // before the client, whose handler uses it
  // Telemetry.telemetry_dropped on the first and the latest message: what the agent could not
  // hand to the link while we listened. I/O thread only until the client stops.
  std::optional<std::uint64_t> first_dropped;
  std::uint64_t last_dropped = 0;
  auto client = MakeClient(link);
  client->OnMessage("telemetry", [&](const google::protobuf::Message& message) {
    if (watch.count > 0 && received.load() >= watch.count) return;
    const auto& telemetry = static_cast<const kapfix::v1::Telemetry&>(message);
    if (!first_dropped) first_dropped = telemetry.telemetry_dropped();
    last_dropped = telemetry.telemetry_dropped();
    if (!watch.summary) PrintLine(kapfix::ctl::TelemetryText(telemetry));
    received.fetch_add(1);
  });
  client->Start();
  const auto start = Clock::now();
  const auto duration = std::chrono::duration<double>(watch.duration_s);
  int code = kOk;
  while (!g_interrupted.load() && (watch.count <= 0 || received.load() < watch.count)) {
    if (watch.duration_s > 0 && Clock::now() - start >= duration) break;
    if (!LinkAlive(*client, link, start)) {
      code = LinkDown(*client, link);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const std::uint64_t gaps = client->SequenceGaps("telemetry");
  client->Stop();  // the handler's variables are ours from here on
  if (watch.summary) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    PrintLine("watch telemetry=" + std::to_string(received.load()) +
              " sequence_gaps=" + std::to_string(gaps) +
              " dropped_by_agent=" + std::to_string(last_dropped - first_dropped.value_or(0)) +
              " seconds=" + SecondsText(seconds));
  }
  return code;
}

int RunSet(const LinkArguments& link, const std::string& key, const std::string& value) {
  std::string error;
  auto command = kapfix::ctl::MakeSetCommand(key, value, &error);
  if (!command) {
    Error(error);
    return kBadArguments;
  }
  auto client = MakeClient(link);
  client->Start();
  const int code = Send(*client, link, std::move(*command));
  if (code == kOk) PrintLine("ok");
  return code;
}

int RunSimple(const LinkArguments& link, Command command) {
  auto client = MakeClient(link);
  client->Start();
  const int code = Send(*client, link, std::move(command));
  if (code == kOk) PrintLine("ok");
  return code;
}

// Messages of one topic handed from the I/O thread to the main thread; only those that
// arrive once armed (right before the command is sent), so an older report cannot pass for
// the answer.
template <typename T>
class Inbox {
 public:
  void Arm() { armed_.store(true); }
  void Put(const T& message) {
    if (!armed_.load()) return;
    {
      const std::lock_guard lock(mutex_);
      messages_.push_back(message);
    }
    arrived_.notify_one();
  }
  std::optional<T> Take(std::chrono::milliseconds wait) {
    std::unique_lock lock(mutex_);
    if (!arrived_.wait_for(lock, wait, [this] { return !messages_.empty(); })) return std::nullopt;
    T message = std::move(messages_.front());
    messages_.pop_front();
    return message;
  }

 private:
  std::atomic<bool> armed_{false};
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::deque<T> messages_;
};

int RunSsp(const LinkArguments& link, bool wait, unsigned frames) {
  Command command;
  command.mutable_set_mode()->set_mode(kapfix::v1::MODE_SSP);
  if (frames > 0) command.mutable_set_mode()->set_deadline_frames(frames);
  if (!wait) return RunSimple(link, std::move(command));

  Inbox<kapfix::v1::SliceReport> reports;  // before the client, whose handler fills it
  auto client = MakeClient(link);
  client->OnMessage("slices", [&](const google::protobuf::Message& message) {
    reports.Put(static_cast<const kapfix::v1::SliceReport&>(message));
  });
  client->Start();
  if (!StreamsReady(*client, link)) return LinkDown(*client, link);
  reports.Arm();
  const int code = Send(*client, link, std::move(command));
  if (code != kOk) return code;
  while (!g_interrupted.load()) {
    const auto report = reports.Take(std::chrono::milliseconds(50));
    if (report) {
      PrintLine(kapfix::ctl::SliceReportText(*report));
      if (report->finished()) return kOk;
    } else if (!client->Status().up) {
      return LinkDown(*client, link);
    }
  }
  return kOk;
}

int RunPhoto(const LinkArguments& link, const std::string& save_folder, const std::string& note) {
  Command command;
  command.mutable_take_photo()->set_note(note);
  if (save_folder.empty()) return RunSimple(link, std::move(command));

  if (std::string why; !kapfix::link::PrepareSaveFolder(save_folder, &why)) {
    Error("--save: " + why);
    return kBadArguments;
  }
  // Before the client: its I/O thread uses them until the client is destroyed.
  kapfix::link::PhotoAssembler assembler;  // used on the I/O thread only
  Inbox<kapfix::link::AssembledPhoto> photos;
  auto client = MakeClient(link);
  client->OnMessage("photo", [&](const google::protobuf::Message& message) {
    if (auto photo = assembler.Add(static_cast<const kapfix::v1::Photo&>(message))) {
      photos.Put(*photo);
    }
  });
  client->Start();
  if (!StreamsReady(*client, link)) return LinkDown(*client, link);
  photos.Arm();
  const int code = Send(*client, link, std::move(command));
  if (code != kOk) return code;
  while (!g_interrupted.load()) {
    if (const auto photo = photos.Take(std::chrono::milliseconds(50))) {
      try {
        PrintLine(kapfix::link::SavePhotoWithSidecar(*photo, save_folder).string());
      } catch (const std::exception& error) {
        Error(error.what());
        return kBadArguments;
      }
      return kOk;
    }
    if (!client->Status().up) return LinkDown(*client, link);
  }
  return kOk;
}

// What a station asks for when the link comes back (as the Qt station's LinkResync): the
// agent's state, its latest SSP result again, and every stored photo taken at or after
// `photos_since_us`, which are saved in `save_folder`. The reply names those photos, so we
// know when we have caught up; other photos that arrive meanwhile (taken now) are kept too.
int RunResync(const LinkArguments& link, std::int64_t photos_since_us,
              const std::string& save_folder) {
  const auto start = Clock::now();
  if (std::string why;
      !save_folder.empty() && !kapfix::link::PrepareSaveFolder(save_folder, &why)) {
    Error("--save: " + why);
    return kBadArguments;
  }
  // Before the client: its I/O thread uses them until the client is destroyed.
  kapfix::link::PhotoAssembler assembler;  // used on the I/O thread only
  Inbox<kapfix::link::AssembledPhoto> photos;
  Inbox<kapfix::v1::SliceReport> reports;
  std::mutex telemetry_mutex;  // guards latest_telemetry
  std::optional<kapfix::v1::Telemetry> latest_telemetry;
  auto client = MakeClient(link);
  if (!save_folder.empty()) {
    client->OnMessage("photo", [&](const google::protobuf::Message& message) {
      if (auto photo = assembler.Add(static_cast<const kapfix::v1::Photo&>(message))) {
        photos.Put(*photo);
      }
    });
  }
  client->OnMessage("slices", [&](const google::protobuf::Message& message) {
    reports.Put(static_cast<const kapfix::v1::SliceReport&>(message));
  });
  // Telemetry flows with every frame: subscribed to it, StreamsReady returns within a frame
  // instead of waiting up to a second for the agent's heartbeat. Its latest line is printed.
  client->OnMessage("telemetry", [&](const google::protobuf::Message& message) {
    const std::lock_guard lock(telemetry_mutex);
    latest_telemetry = static_cast<const kapfix::v1::Telemetry&>(message);
  });
  client->Start();
  if (!StreamsReady(*client, link)) return LinkDown(*client, link);
  if (!save_folder.empty()) photos.Arm();
  reports.Arm();
  Command command;
  command.mutable_request_state()->set_resend_photos_since_us(photos_since_us);
  command.mutable_request_state()->set_resend_slice_report(true);
  kapfix::v1::Reply reply;
  const int code = Send(*client, link, std::move(command), &reply);
  if (code != kOk) return code;
  std::cout << kapfix::ctl::StateText(reply.state());
  std::cout.flush();

  // The agent republishes its SSP result only when it has one.
  bool report_pending = reply.state().has_last_slice_report();
  std::set<std::string> missing(reply.photos_resent().begin(), reply.photos_resent().end());
  std::size_t saved = 0;
  const auto deadline = Clock::now() + link.timeout();
  while (report_pending || !missing.empty()) {
    if (g_interrupted.load()) return kNoAnswer;
    if (Clock::now() >= deadline || !client->Status().up) {
      Error("resync incomplete: " + std::to_string(missing.size()) + " of " +
            std::to_string(reply.photos_resent_size()) + " photos" +
            (report_pending ? " and the SSP result" : "") + " not received within " +
            std::to_string(link.timeout_ms) + " ms");
      return kNoAnswer;
    }
    if (const auto report = reports.Take(std::chrono::milliseconds(0))) {
      if (report->finished()) {
        PrintLine(kapfix::ctl::SliceReportText(*report));
        report_pending = false;
      }
    }
    if (const auto photo = photos.Take(std::chrono::milliseconds(20))) {
      try {
        PrintLine("photo " + kapfix::link::SavePhotoWithSidecar(*photo, save_folder).string());
      } catch (const std::exception& error) {
        Error(error.what());
        return kBadArguments;
      }
      missing.erase(photo->metadata.file_name());
      ++saved;
    }
  }
  {
    const std::lock_guard lock(telemetry_mutex);
    if (latest_telemetry) PrintLine(kapfix::ctl::TelemetryText(*latest_telemetry));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  PrintLine("resync photos_resent=" + std::to_string(reply.photos_resent_size()) +
            " photos_saved=" + std::to_string(saved) + " seconds=" + SecondsText(seconds));
  return kOk;
}

int RunRecord(const LinkArguments& link, const std::string& file, int count, double duration_s) {
  std::optional<kapfix::link::SessionRecorder> recorder;
  try {
    recorder.emplace(file);
  } catch (const std::exception& error) {
    Error(error.what());
    return kBadArguments;
  }
  // Before the client: its I/O thread uses them until the client is destroyed.
  std::mutex mutex;  // guards recorder and write_error (I/O thread writes, main flushes)
  std::string write_error;
  std::atomic<int> recorded{0};
  auto client = MakeClient(link);
  client->OnRawMessage([&](std::string_view topic, std::string_view payload) {
    if (count > 0 && recorded.load() >= count) return;
    const std::lock_guard lock(mutex);
    try {
      recorder->Write(topic, payload, kapfix::v1::NowMicros());
      recorded.fetch_add(1);
    } catch (const std::exception& error) {
      write_error = error.what();
    }
  });
  client->Start();
  const auto start = Clock::now();
  int code = kOk;
  while (!g_interrupted.load() && (count <= 0 || recorded.load() < count)) {
    if (duration_s > 0 && Clock::now() - start >= std::chrono::duration<double>(duration_s)) {
      break;
    }
    {
      const std::lock_guard lock(mutex);
      if (!write_error.empty()) {
        Error(write_error);
        return kBadArguments;
      }
    }
    if (!LinkAlive(*client, link, start)) {
      code = LinkDown(*client, link);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  client->Stop();  // no more writes from the I/O thread
  recorder->Flush();
  std::cerr << "kapfix-ctl: recorded " << recorded.load() << " messages to " << file << std::endl;
  return code;
}

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-ctl: command a kapfix-agent and read its streams (a headless station)"};
  app.footer(std::string(kExitCodes));
  app.require_subcommand(1);

  LinkArguments link;
  app.add_option("--agent", link.host, "agent host name or address")->capture_default_str();
  app.add_option("--command-port", link.command_port, "agent command port (ROUTER)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535));
  app.add_option("--stream-port", link.stream_port, "agent stream port (PUB)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535));
  app.add_option("--timeout", link.timeout_ms,
                 "[ms] wait this long for a reply, or for any message from the agent")
      ->capture_default_str()
      ->check(CLI::Range(1, 3'600'000));
  app.add_option("--agent-id", link.agent_id,
                 "address only the agent with this id (default: whichever listens)");
  auto* key_option =
      app.add_option("--key", link.key_file,
                     "this station's secret key file (kapfix-keygen NAME writes NAME.key)")
          ->check(CLI::ExistingFile);
  auto* agent_key_option =
      app.add_option("--agent-key", link.agent_key_file,
                     "the agent's public key file (its .pub): with --key, the link uses CurveZMQ")
          ->check(CLI::ExistingFile);
  key_option->needs(agent_key_option);
  agent_key_option->needs(key_option);

  bool json = false;
  auto* status = app.add_subcommand("status", "print the agent's mode and settings");
  status->add_flag("--json", json, "print the AgentState as JSON");

  WatchOptions watch_options;
  auto* watch = app.add_subcommand("watch", "print one line per telemetry message");
  watch->add_option("--count", watch_options.count, "stop after N messages (default: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  watch->add_option("--duration", watch_options.duration_s, "[s] stop after this long")
      ->check(CLI::NonNegativeNumber);
  watch->add_flag("--summary", watch_options.summary,
                  "instead of a line per message, print one line at the end: telemetry "
                  "messages received, sequence gaps (messages lost on the link), messages the "
                  "agent dropped before the link, seconds");

  std::string key;
  std::string value;
  auto* set = app.add_subcommand("set", "change one setting");
  set->footer(kapfix::ctl::SettingKeysHelp());
  set->add_option("key", key, "setting to change (listed below)")->required();
  set->add_option("value", value, "its new value")->required();

  bool wait = false;
  unsigned ssp_frames = 0;
  auto* ssp = app.add_subcommand("ssp", "start the Slice Selection Process");
  ssp->add_flag("--wait", wait,
                "follow its progress until it finishes and print the recommended slice");
  ssp->add_option("--frames", ssp_frames, "deadline in frames (default: the agent's)")
      ->check(CLI::PositiveNumber);

  unsigned slice_index = 0;
  auto* slice = app.add_subcommand("slice", "fixate on slice N (1 = top)");
  slice->add_option("N", slice_index, "slice index")->required();

  auto* fixate = app.add_subcommand("fixate", "store a new reference and hold the view");

  std::string save_folder;
  std::string note;
  auto* photo = app.add_subcommand("photo", "take a stabilised photo on the agent");
  photo->add_option("--save", save_folder,
                    "also receive it and save it with its JSON sidecar in this folder (made "
                    "when missing)");
  photo->add_option("--note", note, "text stored in the photo's sidecar");

  std::int64_t resync_since_us = 0;
  std::string resync_folder;
  auto* resync = app.add_subcommand(
      "resync", "catch up after a link loss: state, latest SSP result, photos taken meanwhile");
  auto* resync_save = resync->add_option("--save", resync_folder,
                                         "save the photos the agent sends again in this folder");
  resync
      ->add_option("--photos-since-us", resync_since_us,
                   "[µs since epoch] ask again for the photos taken at or after this time "
                   "(default 0: none)")
      ->check(CLI::NonNegativeNumber)
      ->needs(resync_save);

  std::string record_file;
  int record_count = 0;
  double record_duration_s = 0;
  auto* record =
      app.add_subcommand("record", "write every stream message to FILE, length-prefixed");
  record->footer(
      "File: the 8 bytes \"KFXREC01\", then per message (little-endian): u64 receive time "
      "[µs since epoch], u32 topic length, topic, u32 payload length, payload (the serialized "
      "kapfix.v1 message).");
  record->add_option("FILE", record_file, "output file")->required();
  record->add_option("--count", record_count, "stop after N messages")
      ->check(CLI::NonNegativeNumber);
  record->add_option("--duration", record_duration_s, "[s] stop after this long")
      ->check(CLI::NonNegativeNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? kOk : kBadArguments;
  }
  if (!link.key_file.empty()) {
    std::string why;
    const auto station = kapfix::link::ReadSecretKeyFile(link.key_file, &why);
    const auto agent =
        station ? kapfix::link::ReadPublicKeyFile(link.agent_key_file, &why) : std::nullopt;
    if (!agent) {
      Error(why);
      return kBadArguments;
    }
    link.curve = kapfix::link::CurveClientKeys{*station, *agent};
  }

  std::signal(SIGINT, OnInterrupt);
  std::signal(SIGTERM, OnInterrupt);
  try {
    if (*status) return RunStatus(link, json);
    if (*watch) return RunWatch(link, watch_options);
    if (*set) return RunSet(link, key, value);
    if (*ssp) return RunSsp(link, wait, ssp_frames);
    if (*slice) {
      Command command;
      command.set_select_slice(slice_index);
      return RunSimple(link, std::move(command));
    }
    if (*fixate) {
      Command command;
      command.mutable_set_mode()->set_mode(kapfix::v1::MODE_FIXATE);
      return RunSimple(link, std::move(command));
    }
    if (*photo) return RunPhoto(link, save_folder, note);
    if (*resync) return RunResync(link, resync_since_us, resync_folder);
    if (*record) return RunRecord(link, record_file, record_count, record_duration_s);
  } catch (const std::runtime_error& error) {
    // The link client refuses an endpoint ZeroMQ cannot read: a bad --agent.
    Error(error.what());
    return kBadArguments;
  }
  return kBadArguments;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& error) {
    Error(std::string("internal error: ") + error.what());
    return kBadArguments;
  }
}
