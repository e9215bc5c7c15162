#include "link/session_reader.hpp"

#include <fcntl.h>
#include <google/protobuf/io/zero_copy_stream_impl.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/session.pb.h"
#include "link/legacy_session_reader.hpp"
#include "link/session_recorder.hpp"

namespace kapfix::link {
namespace {

// True when the file starts with the KFXREC01 magic (read without moving the file offset).
bool StartsWithLegacyMagic(int fd) {
  std::array<char, kLegacySessionMagic.size()> magic{};
  const ssize_t got = ::pread(fd, magic.data(), magic.size(), 0);
  return got == static_cast<ssize_t>(magic.size()) &&
         std::string_view(magic.data(), magic.size()) == kLegacySessionMagic;
}

}  // namespace

SessionReader::SessionReader(const std::string& path) : path_(path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot open '" + path + "': " + std::strerror(errno));
  if (StartsWithLegacyMagic(fd)) {
    ::close(fd);
    legacy_ = std::make_unique<LegacySessionReader>(path);
    format_ = std::string(kLegacySessionMagic);
    return;
  }
  in_ = std::make_unique<google::protobuf::io::FileInputStream>(fd);
  in_->SetCloseOnDelete(true);
  ReadFormatRecord();
}

SessionReader::~SessionReader() = default;

void SessionReader::ReadFormatRecord() {
  kapfix::v1::SessionRecord record;
  bool clean_eof = false;
  if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&record, in_.get(), &clean_eof) ||
      !record.has_format() || record.format().name() != kSessionFormatName) {
    throw std::runtime_error("'" + path_ +
                             "' is not a kapfix session recording: it starts neither with a "
                             "length-delimited kapfix.v1.SessionRecord naming the format \"" +
                             std::string(kSessionFormatName) + "\" nor with the old magic " +
                             std::string(kLegacySessionMagic));
  }
  const std::uint32_t version = record.format().version();
  if (version != kSessionFormatVersion) {
    throw std::runtime_error("'" + path_ + "' is a " + std::string(kSessionFormatName) +
                             " recording of version " + std::to_string(version) +
                             "; this build reads version " + std::to_string(kSessionFormatVersion) +
                             " and the old " + std::string(kLegacySessionMagic));
  }
  format_ = std::string(kSessionFormatName) + " " + std::to_string(version);
}

std::optional<RecordedMessage> SessionReader::NextLegacy() {
  std::optional<RecordedMessage> message = legacy_->Next();
  if (!message) error_ = legacy_->error();
  return message;
}

std::optional<RecordedMessage> SessionReader::Next() {
  if (legacy_) return NextLegacy();
  if (!error_.empty()) return std::nullopt;
  kapfix::v1::SessionRecord record;
  while (true) {
    const std::int64_t offset = in_->ByteCount();  // [bytes] where this record starts
    bool clean_eof = false;
    if (!google::protobuf::util::ParseDelimitedFromZeroCopyStream(&record, in_.get(), &clean_eof)) {
      if (!clean_eof) {
        error_ = "'" + path_ + "' is cut short or corrupted in the record at byte " +
                 std::to_string(offset) + " (every message before it was read)";
      }
      return std::nullopt;
    }
    if (record.has_format()) {
      error_ = "'" + path_ + "' holds a second format record at byte " + std::to_string(offset);
      return std::nullopt;
    }
    if (!record.has_message()) continue;  // a record kind this build does not know: skip it
    kapfix::v1::RecordedMessage& recorded = *record.mutable_message();
    if (recorded.payload().size() > kapfix::v1::kMaxMessageBytes) {
      error_ = "'" + path_ + "' holds a message of " + std::to_string(recorded.payload().size()) +
               " bytes at byte " + std::to_string(offset) + ", more than a link message's " +
               std::to_string(kapfix::v1::kMaxMessageBytes);
      return std::nullopt;
    }
    return RecordedMessage{.receive_time_us = recorded.receive_time_us(),
                           .topic = std::move(*recorded.mutable_topic()),
                           .payload = std::move(*recorded.mutable_payload())};
  }
}

}  // namespace kapfix::link
