#include "link/envelope.hpp"

#include "kapfix/v1/envelope_codec.hpp"
#include "link/topic_table.hpp"

namespace kapfix::link {

Envelope Encode(const google::protobuf::Message& message) {
  return Envelope{TopicFor(message), message.SerializeAsString()};
}

bool DecodeEnvelope(std::string_view topic, std::string_view bytes, google::protobuf::Message* out,
                    std::size_t max_bytes, std::string* error, kapfix::v1::ErrorCode* code) {
  const auto fail = [&](kapfix::v1::ErrorCode value, std::string reason) {
    if (error != nullptr) *error = std::move(reason);
    if (code != nullptr) *code = value;
    return false;
  };
  if (out == nullptr) {
    return fail(kapfix::v1::ERROR_CODE_INTERNAL, "Decode was given no message to decode into");
  }
  const std::string expected = TopicFor(*out);
  if (topic != expected) {
    out->Clear();
    return fail(kapfix::v1::ERROR_CODE_MALFORMED,
                "topic '" + kapfix::v1::Printable(topic) + "' does not carry " +
                    out->GetDescriptor()->full_name() + " (its topic is '" + expected + "')");
  }
  return kapfix::v1::Decode(bytes, out, max_bytes, error, code);
}

}  // namespace kapfix::link
