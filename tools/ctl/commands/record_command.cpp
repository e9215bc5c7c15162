// `kapfix-ctl record FILE`: every stream message written to a session file.
#include <atomic>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "kapfix/v1/envelope_codec.hpp"
#include "link/session_recorder.hpp"
#include "tools/ctl/commands/command.hpp"
#include "tools/ctl/commands/command_link.hpp"
#include "tools/ctl/commands/command_output.hpp"
#include "tools/ctl/commands/interrupt.hpp"

namespace kapfix::ctl {
namespace {

struct RecordArguments {
  std::string file;
  int count = 0;          // [messages] stop after this many; 0 = no limit
  double duration_s = 0;  // [s] stop after this long; 0 = no limit
};

int RunRecord(const LinkArguments& link, const RecordArguments& arguments) {
  const std::string& file = arguments.file;
  const int count = arguments.count;
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
  while (!Interrupted() && (count <= 0 || recorded.load() < count)) {
    if (arguments.duration_s > 0 &&
        Clock::now() - start >= std::chrono::duration<double>(arguments.duration_s)) {
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

}  // namespace

void AddRecordCommand(CLI::App& app, const LinkArguments& link, CommandRun* run) {
  auto arguments = std::make_shared<RecordArguments>();
  auto* record =
      app.add_subcommand("record", "write every stream message to FILE, length-prefixed");
  record->footer(
      "File: length-delimited kapfix.v1.SessionRecord messages (proto/kapfix/v1/session.proto; "
      "a varint size, then the record), readable by any protobuf client: first the format "
      "(\"kapfix-session\", version 1), then per message its receive time [µs since epoch], "
      "topic and payload (the serialized kapfix.v1 message).");
  record->add_option("FILE", arguments->file, "output file")->required();
  record->add_option("--count", arguments->count, "stop after N messages")
      ->check(CLI::NonNegativeNumber);
  record->add_option("--duration", arguments->duration_s, "[s] stop after this long")
      ->check(CLI::NonNegativeNumber);
  record->callback([&link, run, arguments] {
    *run = [&link, arguments] { return RunRecord(link, *arguments); };
  });
}

}  // namespace kapfix::ctl
