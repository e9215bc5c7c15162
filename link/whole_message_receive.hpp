#pragma once

// For the socket threads of kapfix_link's users (includes ZeroMQ: link cppzmq to use it):
// receiving one whole multipart message without keeping more of it than the reader needs.

#include <zmq.h>

#include <cstddef>
#include <cstdint>
#include <vector>
#include <zmq.hpp>

#include "link/bounded_intake.hpp"

namespace kapfix::link {

// What one received message took on the wire, and the connection it came from: what a
// BoundedIntake is told the agent consumed.
struct ReceivedWire {
  bool curve = false;       // in: the socket uses CurveZMQ
  bool skip_first = false;  // in: the first frame is ROUTER's routing id, not sent by the peer
  std::uint64_t bytes = 0;  // [bytes] out: ZmtpWireBytes of every frame the peer sent
  int source_fd = -1;       // out: libzmq's descriptor of the connection (ZMQ_SRCFD)
};

// Blocks for the next message and reads all of its frames, keeping the first `keep` in
// `frames` and discarding the rest; returns how many there were. The frames after the first
// arrive together with it (ZeroMQ delivers whole messages). `wire`, when given, is filled in.
// Throws zmq::error_t: ETERM when the context is shut down, EINTR on a signal (the message is
// then lost).
inline std::size_t ReceiveWholeMessage(zmq::socket_t& socket, std::size_t keep,
                                       std::vector<zmq::message_t>* frames,
                                       ReceivedWire* wire = nullptr) {
  std::size_t count = 0;
  bool more = true;
  while (more) {
    zmq::message_t frame;
    (void)socket.recv(frame, zmq::recv_flags::none);
    more = frame.more();
    if (wire != nullptr && !(wire->skip_first && count == 0)) {
      wire->bytes += ZmtpWireBytes(frame.size(), wire->curve);
      wire->source_fd = zmq_msg_get(frame.handle(), ZMQ_SRCFD);
    }
    if (frames->size() < keep) frames->push_back(std::move(frame));
    ++count;
  }
  return count;
}

}  // namespace kapfix::link
