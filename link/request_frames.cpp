#include "link/request_frames.hpp"

#include <algorithm>

namespace kapfix::link {

RequestFrames ParseRequestFrames(std::span<const std::string_view> kept, std::size_t count) {
  RequestFrames frames;
  std::size_t next = 0;
  if (!kept.empty() && kept[0].empty()) {
    frames.delimiter = true;
    ++next;
  }
  const std::size_t parts = count - std::min(count, next);
  if (parts == 2 && kept.size() >= next + 2) {
    frames.topic = std::string(kept[next]);
    frames.payload = kept[next + 1];
  } else if (parts == 1 && kept.size() >= next + 1) {
    frames.payload = kept[next];
  } else {
    frames.error = "malformed request: expected [topic,] message after the routing id" +
                   std::string(frames.delimiter ? " and the empty delimiter" : "") + ", got " +
                   std::to_string(parts) + " frames";
  }
  return frames;
}

}  // namespace kapfix::link
