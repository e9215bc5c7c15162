#pragma once

// What a command request's frames say, after the routing id that ROUTER adds (SPEC §5): an
// optional empty delimiter frame (a REQ socket sends one), an optional topic frame, and the
// serialized message. Pure (no ZeroMQ), so the multipart fuzz target runs the same code.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace kapfix::link {

// Frames after the routing id the server keeps of a request; the rest are read and dropped
// (issue 15, item 4: a peer's frame count never decides how much the agent keeps).
inline constexpr std::size_t kRequestFramesKept = 3;

struct RequestFrames {
  bool delimiter = false;            // an empty frame came first (the reply copies it)
  std::optional<std::string> topic;  // the topic frame, if one was sent
  std::string_view payload;          // the message; empty when `error` is set
  std::string error;                 // non-empty: malformed, naming the problem
};

// `kept`: the first frames after the routing id (at most kRequestFramesKept are looked at);
// `count`: how many there were after the routing id, in all.
RequestFrames ParseRequestFrames(std::span<const std::string_view> kept, std::size_t count);

}  // namespace kapfix::link
