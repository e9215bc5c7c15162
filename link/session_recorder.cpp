#include "link/session_recorder.hpp"

#include <fcntl.h>
#include <google/protobuf/io/zero_copy_stream_impl.h>
#include <google/protobuf/util/delimited_message_util.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/session.pb.h"
#include "kapfix/v1/version.hpp"

namespace kapfix::link {

SessionRecorder::SessionRecorder(const std::string& path) : path_(path) {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-vararg): open(2) is variadic for its mode
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    throw std::runtime_error("cannot create '" + path + "': " + std::strerror(errno));
  }
  out_ = std::make_unique<google::protobuf::io::FileOutputStream>(fd);
  out_->SetCloseOnDelete(true);
  kapfix::v1::SessionRecord record;
  kapfix::v1::SessionFormat* format = record.mutable_format();
  format->set_name(std::string(kSessionFormatName));
  format->set_version(kSessionFormatVersion);
  format->set_protocol_version(kapfix::v1::kProtocolVersion);
  format->set_started_us(kapfix::v1::NowMicros());
  Append(record);
}

SessionRecorder::~SessionRecorder() = default;  // FileOutputStream flushes and closes

void SessionRecorder::Write(std::string_view topic, std::string_view payload,
                            std::int64_t receive_time_us) {
  kapfix::v1::SessionRecord record;
  kapfix::v1::RecordedMessage* message = record.mutable_message();
  message->set_receive_time_us(receive_time_us);
  message->set_topic(std::string(topic));
  message->set_payload(std::string(payload));
  Append(record);
  ++messages_;
}

void SessionRecorder::Flush() {
  if (!out_->Flush()) {
    throw std::runtime_error("cannot write to '" + path_ + "': " + std::strerror(out_->GetErrno()));
  }
}

void SessionRecorder::Append(const kapfix::v1::SessionRecord& record) {
  if (!google::protobuf::util::SerializeDelimitedToZeroCopyStream(record, out_.get())) {
    throw std::runtime_error("cannot write to '" + path_ + "': " +
                             (out_->GetErrno() != 0 ? std::strerror(out_->GetErrno())
                                                    : "record too large to serialize"));
  }
}

}  // namespace kapfix::link
