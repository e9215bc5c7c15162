// `kapfix-ctl watch`: one line per telemetry message, or one summary line at the end.
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <thread>

#include "kapfix/v1/telemetry.pb.h"
#include "link/topic_names.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/interrupt.hpp"
#include "tools/ctl/message_text.hpp"

namespace kapfix::ctl {
namespace {

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
  client->OnMessage(std::string(kapfix::link::kTelemetryTopic),
                    [&](const google::protobuf::Message& message) {
                      if (watch.count > 0 && received.load() >= watch.count) return;
                      const auto& telemetry = static_cast<const kapfix::v1::Telemetry&>(message);
                      if (!first_dropped) first_dropped = telemetry.telemetry_dropped();
                      last_dropped = telemetry.telemetry_dropped();
                      if (!watch.summary) PrintLine(TelemetryText(telemetry));
                      received.fetch_add(1);
                    });
  client->Start();
  const auto start = Clock::now();
  const auto duration = std::chrono::duration<double>(watch.duration_s);
  int code = kOk;
  while (!Interrupted() && (watch.count <= 0 || received.load() < watch.count)) {
    if (watch.duration_s > 0 && Clock::now() - start >= duration) break;
    if (!LinkAlive(*client, link, start)) {
      code = LinkDown(*client, link);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const std::uint64_t gaps = client->SequenceGaps(kapfix::link::kTelemetryTopic);
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

}  // namespace

void AddWatchCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto options = std::make_shared<WatchOptions>();
  auto* watch = app.add_subcommand("watch", "print one line per telemetry message");
  watch->add_option("--count", options->count, "stop after N messages (default: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  watch->add_option("--duration", options->duration_s, "[s] stop after this long")
      ->check(CLI::NonNegativeNumber);
  watch->add_flag("--summary", options->summary,
                  "instead of a line per message, print one line at the end: telemetry "
                  "messages received, sequence gaps (messages lost on the link, a burst's tail "
                  "included), messages the "
                  "agent dropped before the link, seconds");
  watch->callback(
      [&link, run, options] { *run = [&link, options] { return RunWatch(link, *options); }; });
}

}  // namespace kapfix::ctl
