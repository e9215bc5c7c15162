#pragma once

// The bodies of the link's libFuzzer targets (tests/fuzz/README.md), shared with the corpus
// replay test so that both run the same code. Any input may be refused; none may crash, hang
// or break a promise of the link, which aborts (invariant.hpp).

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "kapfix/v1/command.pb.h"

namespace kapfix::fuzz {

// The first byte of a stream input that selects `topic`: its index in kapfix::link::Topics().
// A byte past the last topic (what an unknown `topic` gets) stands for an unknown topic.
std::uint8_t TopicByte(std::string_view topic);

// A station receiving one message on the agent's streams: the first byte picks the topic
// (TopicByte), the rest is the payload, decoded as the station decodes every stream topic
// (NewMessageForTopic, DecodeEnvelope). Checks that a refused message is left empty with a
// reason, and that an accepted one has our protocol version, re-encodes to itself and is
// never readable as another topic's type. True when the station would use the message.
bool FuzzStreamMessage(const std::uint8_t* data, std::size_t size);

// The agent receiving the bytes as one command request from a station (CommandIntake, over
// the fake AgentControl of tests/link), then the same bytes replayed. Checks that the reply
// is well-formed and readable at the station; that a command is executed exactly when it is
// accepted, and then addressed to this agent, numbered and within CommandLimits
// (executed_command_check.hpp); and that the replay is never executed. Returns the first
// reply's error: ERROR_CODE_UNSPECIFIED when the command was executed.
kapfix::v1::ErrorCode FuzzCommand(const std::uint8_t* data, std::size_t size);

// The agent receiving one multipart request (issue 15): the input is split into frames, each
// a length byte L and L bytes, the rest of the input the last frame; the frames go through
// ParseRequestFrames as the server keeps them (at most kRequestFramesKept, the rest only
// counted), and an accepted envelope's payload to CommandIntake. Checks that only [delimiter,]
// [topic,] message is accepted, that a refusal names the frame count, and that the reply is
// well-formed. Returns the number of frames.
std::size_t FuzzMultipartRequest(const std::uint8_t* data, std::size_t size);

// The agent's stream socket receiving a sequence of subscription messages from a few peers
// (issue 15): the input is records of a peer byte (low 3 bits: which of 8 peers; bit 7: that
// peer disconnects first and a new connection takes its place), a length byte L and L bytes
// of message. Each goes through the SubscriptionBook the publisher uses (with small bounds),
// and its decisions are applied to a model of libzmq's subscriptions. Checks that no peer
// ever holds more subscriptions than the bound nor a longer one, that only admitted topics
// are unsubscribed, that the book's count per peer matches the model, and that the book never
// remembers more peers than its bound. Returns the number of subscriptions applied.
std::size_t FuzzSubscriptions(const std::uint8_t* data, std::size_t size);

// Drops protobuf's log lines (e.g. one per string field with invalid UTF-8), which would
// flood a fuzzer's output and slow it down.
void SilenceProtobufLogs();

}  // namespace kapfix::fuzz
