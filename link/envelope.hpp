#pragma once

// One kapfix.v1 message as it travels on the link, independent of ZeroMQ: its topic
// (topic_names.hpp; first frame) and its serialized bytes (second frame). Decoding checks the
// topic is the one the type travels under, then size, well-formedness and protocol version
// (kapfix::v1::Decode) before anything reads a field.

#include <google/protobuf/message.h>

#include <cstddef>
#include <string>
#include <string_view>

#include "kapfix/v1/command.pb.h"

namespace kapfix::link {

struct Envelope {
  std::string topic;    // TopicFor(message)
  std::string payload;  // serialized message
};

// Topic and serialized bytes of a message (stamp its header first).
Envelope Encode(const google::protobuf::Message& message);

// kapfix::v1::Decode() that also checks `topic` is the one `out`'s type travels under, so bytes
// published under one topic are never read as another type. On failure returns false, leaves
// `out` cleared, and sets `error` and `code` (both optional).
bool DecodeEnvelope(std::string_view topic, std::string_view bytes, google::protobuf::Message* out,
                    std::size_t max_bytes, std::string* error,
                    kapfix::v1::ErrorCode* code = nullptr);

}  // namespace kapfix::link
