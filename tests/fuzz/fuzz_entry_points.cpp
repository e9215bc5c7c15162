#include "tests/fuzz/fuzz_entry_points.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <google/protobuf/stubs/logging.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "agent/server/command_intake.hpp"
#include "agent/server/subscription_book.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/envelope.hpp"
#include "link/request_frames.hpp"
#include "link/topic_table.hpp"
#include "tests/fuzz/executed_command_check.hpp"
#include "tests/fuzz/invariant.hpp"
#include "tests/link/fake_agent_control.hpp"

namespace kapfix::fuzz {
namespace {

using google::protobuf::Message;
using kapfix::v1::ErrorCode;

constexpr const char* kAgentId = "kapfix-agent";
// A ROUTER routing id as libzmq makes them: binary, 5 bytes.
constexpr std::string_view kStation("\0\x80\x00\x41\xa7", 5);

std::string_view TopicOf(std::uint8_t byte) {
  const std::vector<std::string>& topics = kapfix::link::Topics();
  if (byte < topics.size()) return topics[byte];
  return "unknown";
}

std::string_view Bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

const kapfix::v1::Header& HeaderOf(const Message& message) {
  const auto* field = message.GetDescriptor()->FindFieldByNumber(1);
  return static_cast<const kapfix::v1::Header&>(
      message.GetReflection()->GetMessage(message, field));
}

// A station records and replays what it receives (SessionRecorder): the message encodes to
// bytes that decode to the same message, under the same topic.
void RequireRoundTrip(std::string_view topic, const Message& message) {
  const kapfix::link::Envelope again = kapfix::link::Encode(message);
  Require(again.topic == topic, "a decoded message encodes under the topic it came on");
  const std::unique_ptr<Message> copy = kapfix::link::NewMessageForTopic(topic);
  std::string error;
  if (!kapfix::link::DecodeEnvelope(topic, again.payload, copy.get(), kapfix::v1::kMaxMessageBytes,
                                    &error)) {
    Broken("a decoded message, encoded again, does not decode: " + error);
  }
  Require(copy->SerializeAsString() == again.payload, "a decoded message encodes to itself");
}

// Bytes published under one topic are never read as another type.
void RequireNoOtherTypeReads(std::string_view topic, std::string_view payload) {
  for (const std::string& other : kapfix::link::Topics()) {
    if (other == topic) continue;
    const std::unique_ptr<Message> message = kapfix::link::NewMessageForTopic(other);
    Require(!kapfix::link::DecodeEnvelope(topic, payload, message.get(),
                                          kapfix::v1::kMaxMessageBytes, nullptr),
            "bytes published under one topic decode as another topic's type");
  }
}

// What the station needs of every reply: ok, or an error with a reason; and, stamped as the
// server stamps it, bytes that decode at the station (no invalid UTF-8 echoed in a reason).
void RequireWellFormed(const kapfix::v1::Reply& answer, std::uint64_t command_sequence) {
  const bool refused = answer.error() != kapfix::v1::ERROR_CODE_UNSPECIFIED;
  Require(answer.ok() != refused, "a reply is ok or carries an error, never both or neither");
  Require(!refused || !answer.reason().empty(), "a refusal gives a reason");
  kapfix::v1::Reply sent = answer;
  sent.set_command_sequence(command_sequence);
  kapfix::v1::Stamp(sent.mutable_header(), kAgentId, 1);
  kapfix::v1::Reply received;
  std::string error;
  if (!kapfix::link::DecodeEnvelope("reply", sent.SerializeAsString(), &received,
                                    kapfix::v1::kMaxMessageBytes, &error)) {
    Broken("the station cannot read the agent's reply: " + error);
  }
}

void RequireExecutedAsPromised(const kapfix::v1::Command& command, std::uint64_t command_sequence,
                               const kapfix::v1::AgentState& before) {
  const kapfix::v1::Header& header = command.header();
  Require(header.protocol_version() == kapfix::v1::kProtocolVersion,
          "an executed command speaks our protocol version");
  Require(header.sequence() > 0 && header.sequence() == command_sequence,
          "an executed command is numbered, and its reply names that number");
  Require(header.agent_id().empty() || header.agent_id() == kAgentId,
          "an executed command is addressed to this agent");
  RequireWithinLimits(command, before, kapfix::agent::CommandLimits{});
}

}  // namespace

std::uint8_t TopicByte(std::string_view topic) {
  const std::vector<std::string>& topics = kapfix::link::Topics();
  return static_cast<std::uint8_t>(std::find(topics.begin(), topics.end(), topic) - topics.begin());
}

bool FuzzStreamMessage(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return false;
  const std::string_view topic = TopicOf(data[0]);
  const std::string_view payload = Bytes(data + 1, size - 1);
  const std::unique_ptr<Message> message = kapfix::link::NewMessageForTopic(topic);
  if (message == nullptr) {
    const auto& topics = kapfix::link::Topics();
    Require(std::find(topics.begin(), topics.end(), topic) == topics.end(),
            "every topic of Topics() has a message type");
    return false;
  }
  std::string error;
  ErrorCode code = kapfix::v1::ERROR_CODE_UNSPECIFIED;
  if (!kapfix::link::DecodeEnvelope(topic, payload, message.get(), kapfix::v1::kMaxMessageBytes,
                                    &error, &code)) {
    Require(message->ByteSizeLong() == 0, "a refused message is left empty");
    Require(!error.empty() && code != kapfix::v1::ERROR_CODE_UNSPECIFIED,
            "a refused message comes with a reason and an error code");
    return false;
  }
  Require(HeaderOf(*message).protocol_version() == kapfix::v1::kProtocolVersion,
          "an accepted message speaks our protocol version");
  RequireRoundTrip(topic, *message);
  RequireNoOtherTypeReads(topic, payload);
  return true;
}

ErrorCode FuzzCommand(const std::uint8_t* data, std::size_t size) {
  const std::string_view payload = Bytes(data, size);
  kapfix::testing::FakeAgentControl control;
  const kapfix::v1::AgentState before = control.State();
  kapfix::agent::CommandIntake intake(control, kAgentId);

  const auto first = intake.Answer(kStation, "command", payload);
  RequireWellFormed(first.reply, first.command_sequence);
  const std::vector<kapfix::v1::Command> executed = control.commands();
  Require(executed.size() == (first.reply.ok() ? 1U : 0U),
          "a command is executed exactly when it is accepted");
  if (!executed.empty()) {
    RequireExecutedAsPromised(executed.front(), first.command_sequence, before);
  }

  // The same bytes again, as a REQ socket sends them (no topic frame): a replay.
  const auto replay = intake.Answer(kStation, std::nullopt, payload);
  RequireWellFormed(replay.reply, replay.command_sequence);
  Require(control.commands().size() == executed.size(), "a replayed command is never executed");
  Require(!first.station_heard || replay.reply.error() == kapfix::v1::ERROR_CODE_STALE_SEQUENCE,
          "a replayed command is refused as stale");
  return first.reply.error();
}

std::size_t FuzzMultipartRequest(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string_view> kept;
  std::size_t count = 0;
  std::size_t at = 0;
  while (at < size) {
    const std::size_t length = data[at];
    const bool last = at + 1 + length >= size;
    const std::string_view frame =
        last ? Bytes(data + at, size - at) : Bytes(data + at + 1, length);
    if (kept.size() < kapfix::link::kRequestFramesKept) kept.push_back(frame);
    ++count;
    at = last ? size : at + 1 + length;
  }
  const kapfix::link::RequestFrames frames = kapfix::link::ParseRequestFrames(kept, count);
  const std::size_t parts = count - (frames.delimiter ? 1U : 0U);
  Require(frames.error.empty() == (parts == 1 || parts == 2),
          "exactly [delimiter,] [topic,] message is accepted");
  if (!frames.error.empty()) {
    Require(frames.error.find(std::to_string(parts) + " frames") != std::string::npos,
            "a refused request names its frame count");
    return count;
  }
  kapfix::testing::FakeAgentControl control;
  kapfix::agent::CommandIntake intake(control, kAgentId);
  const auto outcome = intake.Answer(kStation, frames.topic, frames.payload);
  RequireWellFormed(outcome.reply, outcome.command_sequence);
  return count;
}

std::size_t FuzzSubscriptions(const std::uint8_t* data, std::size_t size) {
  using kapfix::agent::SubscriptionBook;
  constexpr kapfix::agent::SubscriptionBookOptions kOptions{
      .max_topics_per_peer = 4, .max_topic_bytes = 16, .max_peers = 3};
  constexpr std::size_t kPeers = 8;
  // Each of the 8 slots is one connection at a time; a disconnect gives the slot a new one.
  std::array<std::uint64_t, kPeers> generation{};
  const auto name = [&](std::size_t slot) {
    return std::to_string(slot) + "/" + std::to_string(generation[slot]);
  };
  std::set<std::string> connected;
  for (std::size_t slot = 0; slot < kPeers; ++slot) connected.insert(name(slot));
  // What libzmq would hold: the subscriptions applied, per connection.
  std::map<std::string, std::set<std::string>> applied;
  SubscriptionBook book(kOptions,
                        [&](const std::string& peer) { return connected.contains(peer); });
  std::size_t subscribed = 0;
  std::size_t at = 0;
  while (at + 2 <= size) {
    const std::uint8_t peer_byte = data[at];
    const std::size_t length = std::min<std::size_t>(data[at + 1], size - at - 2);
    const std::string_view message(reinterpret_cast<const char*>(data + at + 2), length);
    at += 2 + length;
    const std::size_t slot = peer_byte & 0x07U;
    if ((peer_byte & 0x80U) != 0) {
      // libzmq drops a closed connection's subscriptions itself.
      connected.erase(name(slot));
      applied.erase(name(slot));
      ++generation[slot];
      connected.insert(name(slot));
    }
    const std::string peer = name(slot);
    const SubscriptionBook::Decision decision = book.Receive(peer, message);
    std::set<std::string>& mine = applied[peer];
    if (decision.action == SubscriptionBook::Action::kSubscribe) {
      Require(message.size() >= 1 && message.front() == 1 && decision.topic == message.substr(1),
              "a subscription applies the topic it carries");
      Require(decision.topic.size() <= kOptions.max_topic_bytes, "a subscription over the length");
      Require(mine.emplace(decision.topic).second, "a subscription applied twice");
      Require(mine.size() <= kOptions.max_topics_per_peer, "a peer over its subscriptions");
      ++subscribed;
    } else if (decision.action == SubscriptionBook::Action::kUnsubscribe) {
      Require(message.size() >= 1 && message.front() == 0 && decision.topic == message.substr(1),
              "an unsubscription removes the topic it carries");
      Require(mine.erase(std::string(decision.topic)) == 1,
              "an unsubscription of a topic never applied");
    } else {
      Require(decision.refusal.empty() || (message.size() >= 1 && message.front() == 1),
              "only a subscription is refused with a reason");
    }
    Require(book.TopicsOf(peer) == mine.size(), "the book's count differs from what was applied");
    Require(book.peers() <= kOptions.max_peers, "the book remembers more peers than its bound");
  }
  Require(book.counters().admitted == subscribed, "the admitted count differs");
  return subscribed;
}

void SilenceProtobufLogs() { google::protobuf::SetLogHandler(nullptr); }

}  // namespace kapfix::fuzz
