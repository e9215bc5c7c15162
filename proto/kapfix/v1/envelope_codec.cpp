#include "kapfix/v1/envelope_codec.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/stubs/logging.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstdio>
#include <utility>

namespace kapfix::v1 {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;

// Every message that travels on its own carries `Header header = 1;`.
constexpr int kHeaderField = 1;

bool Fail(ErrorCode value, std::string reason, std::string* error, ErrorCode* code) {
  if (error != nullptr) *error = std::move(reason);
  if (code != nullptr) *code = value;
  return false;
}

}  // namespace

std::string Printable(std::string_view key) {
  constexpr std::size_t kMaxShown = 48;
  std::string out;
  for (std::size_t i = 0; i < key.size() && i < kMaxShown; ++i) {
    const auto c = static_cast<unsigned char>(key[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out.push_back(static_cast<char>(c));
    } else {
      std::array<char, 5> hex{};
      std::snprintf(hex.data(), hex.size(), "\\x%02x", static_cast<unsigned>(c));
      out += hex.data();
    }
  }
  if (key.size() > kMaxShown) out += "...";
  return out;
}

bool Decode(std::string_view bytes, Message* out, std::size_t max_bytes, std::string* error,
            ErrorCode* code) {
  if (out == nullptr) {
    return Fail(ERROR_CODE_INTERNAL, "Decode was given no message to decode into", error, code);
  }
  out->Clear();
  const std::string& type = out->GetDescriptor()->full_name();
  const FieldDescriptor* header_field = out->GetDescriptor()->FindFieldByNumber(kHeaderField);
  if (header_field == nullptr || header_field->type() != FieldDescriptor::TYPE_MESSAGE ||
      header_field->message_type()->full_name() != Header::descriptor()->full_name()) {
    return Fail(ERROR_CODE_INTERNAL, type + " is not a link message (no Header header = 1)", error,
                code);
  }
  if (bytes.size() > max_bytes || bytes.size() > static_cast<std::size_t>(INT_MAX)) {
    return Fail(ERROR_CODE_OVERSIZED,
                "oversized " + type + ": " + std::to_string(bytes.size()) +
                    " bytes exceed the limit of " + std::to_string(max_bytes) + " bytes",
                error, code);
  }
  if (!out->ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
    out->Clear();
    return Fail(ERROR_CODE_MALFORMED,
                "malformed " + type + ": its " + std::to_string(bytes.size()) +
                    " bytes do not parse (truncated, corrupted or not a protobuf message)",
                error, code);
  }
  if (!out->GetReflection()->HasField(*out, header_field)) {
    out->Clear();
    return Fail(ERROR_CODE_MISSING_HEADER,
                type + " carries no header (protocol version, agent id, sequence)", error, code);
  }
  const Message& header = out->GetReflection()->GetMessage(*out, header_field);
  const FieldDescriptor* version_field =
      header.GetDescriptor()->FindFieldByNumber(Header::kProtocolVersionFieldNumber);
  const std::uint32_t version = header.GetReflection()->GetUInt32(header, version_field);
  if (version != kProtocolVersion) {
    out->Clear();
    return Fail(ERROR_CODE_WRONG_VERSION,
                "wrong protocol version in " + type + ": got " + std::to_string(version) +
                    (version == 0 ? " (unset)" : "") + ", this side speaks " +
                    std::to_string(kProtocolVersion),
                error, code);
  }
  return true;
}

namespace {

std::atomic<std::uint64_t> libprotobuf_lines_dropped{0};

void DropBelowFatal(google::protobuf::LogLevel level, const char* filename, int line,
                    const std::string& message) {
  if (level < google::protobuf::LOGLEVEL_FATAL) {
    libprotobuf_lines_dropped.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  std::fprintf(stderr, "[libprotobuf FATAL %s:%d] %s\n", filename, line, message.c_str());
}

}  // namespace

void QuietLibprotobufLog() { google::protobuf::SetLogHandler(&DropBelowFatal); }

std::uint64_t LibprotobufLinesDropped() { return libprotobuf_lines_dropped.load(); }

std::int64_t NowMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void Stamp(Header* header, const std::string& agent_id, std::uint64_t sequence,
           std::uint64_t boot_id) {
  const std::int64_t now = NowMicros();
  header->set_protocol_version(kProtocolVersion);
  header->set_agent_id(agent_id);
  header->set_boot_id(boot_id);
  header->set_sequence(sequence);
  header->set_send_time_us(now);
  if (header->capture_time_us() == 0) header->set_capture_time_us(now);
}

SequenceGuard::SequenceGuard(std::size_t max_senders)
    : max_senders_(std::max<std::size_t>(max_senders, 1)) {}

bool SequenceGuard::Accept(std::string_view sender, std::uint64_t sequence, std::string* error) {
  if (sequence == 0) {
    if (error != nullptr) {
      *error = "sequence number 0 (unset) from '" + Printable(sender) +
               "': messages are numbered from 1";
    }
    return false;
  }
  std::string key(sender);
  auto it = senders_.find(key);
  if (it != senders_.end()) {
    const std::uint64_t last = it->second.last_sequence;
    if (sequence == last) {
      if (error != nullptr) {
        *error = "replayed sequence number " + std::to_string(sequence) + " from '" +
                 Printable(sender) + "': already accepted";
      }
      return false;
    }
    if (sequence < last) {
      if (error != nullptr) {
        *error = "stale sequence number " + std::to_string(sequence) + " from '" +
                 Printable(sender) + "': " + std::to_string(last) + " was already accepted";
      }
      return false;
    }
  } else {
    if (senders_.size() >= max_senders_) EvictLeastRecentlyUsed();
    it = senders_.emplace(std::move(key), Entry{}).first;
  }
  it->second.last_sequence = sequence;
  it->second.last_use = ++use_clock_;
  return true;
}

void SequenceGuard::Forget(std::string_view sender) { senders_.erase(std::string(sender)); }

std::optional<std::uint64_t> SequenceGuard::LastAccepted(std::string_view sender) const {
  const auto it = senders_.find(std::string(sender));
  if (it == senders_.end()) return std::nullopt;
  return it->second.last_sequence;
}

void SequenceGuard::EvictLeastRecentlyUsed() {
  const auto oldest = std::min_element(
      senders_.begin(), senders_.end(),
      [](const auto& a, const auto& b) { return a.second.last_use < b.second.last_use; });
  if (oldest != senders_.end()) senders_.erase(oldest);
}

}  // namespace kapfix::v1
