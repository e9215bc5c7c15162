#pragma once

// For the socket threads of kapfix_link's users (includes ZeroMQ: link cppzmq to use it):
// receiving one whole multipart message without keeping more of it than the reader needs.

#include <cstddef>
#include <vector>
#include <zmq.hpp>

namespace kapfix::link {

// Blocks for the next message and reads all of its frames, keeping the first `keep` in
// `frames` and discarding the rest; returns how many there were. The frames after the first
// arrive together with it (ZeroMQ delivers whole messages). Throws zmq::error_t: ETERM when
// the context is shut down, EINTR on a signal (the message is then lost).
inline std::size_t ReceiveWholeMessage(zmq::socket_t& socket, std::size_t keep,
                                       std::vector<zmq::message_t>* frames) {
  std::size_t count = 0;
  bool more = true;
  while (more) {
    zmq::message_t frame;
    (void)socket.recv(frame, zmq::recv_flags::none);
    more = frame.more();
    if (frames->size() < keep) frames->push_back(std::move(frame));
    ++count;
  }
  return count;
}

}  // namespace kapfix::link
