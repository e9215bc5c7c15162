#pragma once

#include <spdlog/sinks/sink.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "agent/server/stream_sink.hpp"
#include "kapfix/v1/log.pb.h"

namespace kapfix::agent {

// The agent's log lines on the link (topic "log"), so that the station shows them ("photo not
// saved: disk full", "camera lost …"): an spdlog sink added beside the console one. Lines below
// the sink's level stay local. A line logged while publishing (by the link itself) is dropped
// here, before any lock is taken, so the sink can neither recurse nor deadlock on itself.
// Lines are rate-limited in all (issue 15, item 11: a peer that makes the agent log, e.g. with
// refused handshakes, must not flood the stations): a bucket of `burst` lines refilled at
// `lines_per_s`; the next line sent says how many were not.
struct LogRateLimit {
  double burst = 50;        // [lines]
  double lines_per_s = 10;  // [lines/s]
};

class LogPublisher : public spdlog::sinks::sink {
 public:
  explicit LogPublisher(StreamSink& stream, spdlog::level::level_enum level = spdlog::level::info,
                        LogRateLimit limit = {});

  void log(const spdlog::details::log_msg& message) override;
  void flush() override {}
  // The station gets the raw text and formats it itself.
  void set_pattern(const std::string& /*pattern*/) override {}
  void set_formatter(std::unique_ptr<spdlog::formatter> /*formatter*/) override {}

  static kapfix::v1::LogLevel ToProto(spdlog::level::level_enum level);

 private:
  StreamSink& sink_;
  const LogRateLimit limit_;
  std::mutex mutex_;  // guards the bucket: spdlog calls log() from any thread
  double tokens_;     // [lines]
  std::chrono::system_clock::time_point refilled_{};
  std::uint64_t not_sent_ = 0;  // [lines] since the last one sent
};

}  // namespace kapfix::agent
