#include "agent/downlink/log_publisher.hpp"

#include <chrono>
#include <string>

namespace kapfix::agent {
namespace {

thread_local bool publishing = false;  // this thread is inside Publish: do not recurse

}  // namespace

LogPublisher::LogPublisher(StreamSink& stream, spdlog::level::level_enum level) : sink_(stream) {
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
  publishing = true;
  kapfix::v1::Log line;
  line.mutable_header()->set_capture_time_us(
      std::chrono::duration_cast<std::chrono::microseconds>(message.time.time_since_epoch())
          .count());
  line.set_level(ToProto(message.level));
  line.set_text(std::string(message.payload.begin(), message.payload.end()));
  line.set_logger(std::string(message.logger_name.begin(), message.logger_name.end()));
  sink_.Publish(line);
  publishing = false;
}

}  // namespace kapfix::agent
