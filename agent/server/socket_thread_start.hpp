#pragma once

// Internal to kapfix_agent_server (includes ZeroMQ): the start sequence shared by the command
// server and the stream publisher, each of which owns its socket on its own thread.

#include <future>
#include <memory>
#include <string>
#include <thread>
#include <zmq.hpp>

namespace kapfix::agent {

// Gives `impl` a fresh context and runs impl->Run(promise) on impl->thread; returns the
// endpoint the thread bound, or, when binding failed, joins the thread and rethrows its error.
template <typename Impl>
std::string StartSocketThread(Impl* impl) {
  impl->context = std::make_unique<zmq::context_t>(1);
  std::promise<std::string> bound;
  std::future<std::string> endpoint = bound.get_future();
  impl->thread =
      std::thread([impl, promise = std::move(bound)]() mutable { impl->Run(std::move(promise)); });
  try {
    return endpoint.get();
  } catch (...) {
    impl->thread.join();
    impl->context.reset();
    throw;
  }
}

}  // namespace kapfix::agent
