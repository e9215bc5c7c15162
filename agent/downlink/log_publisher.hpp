#pragma once

#include <spdlog/sinks/sink.h>

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
class LogPublisher : public spdlog::sinks::sink {
 public:
  explicit LogPublisher(StreamSink& stream, spdlog::level::level_enum level = spdlog::level::info);

  void log(const spdlog::details::log_msg& message) override;
  void flush() override {}
  // The station gets the raw text and formats it itself.
  void set_pattern(const std::string& /*pattern*/) override {}
  void set_formatter(std::unique_ptr<spdlog::formatter> /*formatter*/) override {}

  static kapfix::v1::LogLevel ToProto(spdlog::level::level_enum level);

 private:
  StreamSink& sink_;
};

}  // namespace kapfix::agent
