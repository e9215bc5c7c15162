#include "agent/downlink/log_publisher.hpp"

#include <algorithm>
#include <chrono>
#include <mutex>
#include <string>
#include <utility>

namespace kapfix::agent {
namespace {

thread_local bool publishing = false;  // this thread is inside Publish: do not recurse

}  // namespace

LogPublisher::LogPublisher(StreamSink& stream, spdlog::level::level_enum level, LogRateLimit limit)
    : sink_(stream), limit_(limit), tokens_(limit.burst) {
  set_level(level);
}

kapfix::v1::LogLevel LogPublisher::ToProto(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::trace:
      return kapfix::v1::LOG_LEVEL_TRACE;
    case spdlog::level::debug:
      return kapfix::v1::LOG_LEVEL_DEBUG;
    case spdlog::level::info:
      return kapfix::v1::LOG_LEVEL_INFO;
    case spdlog::level::warn:
      return kapfix::v1::LOG_LEVEL_WARN;
    case spdlog::level::err:
      return kapfix::v1::LOG_LEVEL_ERROR;
    case spdlog::level::critical:
      return kapfix::v1::LOG_LEVEL_CRITICAL;
    default:
      return kapfix::v1::LOG_LEVEL_UNSPECIFIED;
  }
}

void LogPublisher::log(const spdlog::details::log_msg& message) {
  if (publishing) return;
  std::uint64_t skipped = 0;
  {
    const std::lock_guard lock(mutex_);
    const std::chrono::duration<double> elapsed = message.time - refilled_;
    if (elapsed.count() > 0) {
      tokens_ = std::min(limit_.burst, tokens_ + elapsed.count() * limit_.lines_per_s);
      refilled_ = message.time;
    }
    if (tokens_ < 1) {
      ++not_sent_;
      return;
    }
    tokens_ -= 1;
    std::swap(skipped, not_sent_);
  }
  publishing = true;
  kapfix::v1::Log line;
  line.mutable_header()->set_capture_time_us(
      std::chrono::duration_cast<std::chrono::microseconds>(message.time.time_since_epoch())
          .count());
  line.set_level(ToProto(message.level));
  line.set_text(std::string(message.payload.begin(), message.payload.end()));
  if (skipped > 0) {
    line.mutable_text()->append(" [" + std::to_string(skipped) +
                                " earlier log lines not sent: rate limit]");
  }
  line.set_logger(std::string(message.logger_name.begin(), message.logger_name.end()));
  sink_.Publish(line);
  publishing = false;
}

}  // namespace kapfix::agent
