#pragma once

// Wakes a thread blocked in zmq::poll from any other thread. A ZeroMQ socket belongs to one
// thread, so other threads cannot poke the I/O thread through a socket; an eventfd is a plain
// file descriptor, which zmq_poll watches beside the sockets and which any thread may write.

namespace kapfix::link {

class WakeSignal {
 public:
  WakeSignal();  // throws std::system_error when no eventfd can be made
  ~WakeSignal();
  WakeSignal(const WakeSignal&) = delete;
  WakeSignal& operator=(const WakeSignal&) = delete;

  int fd() const { return fd_; }  // readable while notified
  void Notify();                  // thread-safe, never blocks
  void Clear();                   // by the waiting thread, before looking for work

 private:
  int fd_;
};

}  // namespace kapfix::link
