#pragma once

// Server side of the link (includes ZeroMQ): the start and stop sequences shared by
// the command server and the stream publisher, each of which owns its socket on its own
// thread, and, with CurveZMQ keys, a ZAP handler on another in the same context.

#include <future>
#include <memory>
#include <string>
#include <thread>
#include <zmq.hpp>

#include "link/zap_handler.hpp"

namespace kapfix::link {

// Shuts the context down, which wakes every blocking call on its sockets with ETERM, joins the
// threads and closes the context. Returns promptly; idempotent.
template <typename Impl>
void StopSocketThread(Impl* impl) {
  if (!impl->context) return;
  impl->context->shutdown();
  if (impl->thread.joinable()) impl->thread.join();
  impl->zap.reset();      // joins its thread
  impl->monitor.reset();  // joins its thread
  impl->context.reset();
}

// Gives `impl` a fresh context (and, when impl->options.curve is set, starts the ZAP handler
// in it, before anything binds) and runs impl->Run(promise) on impl->thread; returns the
// endpoint the thread bound, or, when binding failed, joins the thread and rethrows its error.
// `what` names the server in errors and log lines.
template <typename Impl>
std::string StartSocketThread(Impl* impl, const char* what) {
  impl->context = std::make_unique<zmq::context_t>(1);
  if (impl->options.curve) {
    impl->zap = std::make_unique<ZapHandler>(*impl->options.curve, what);
    try {
      impl->zap->Start(*impl->context);
    } catch (...) {
      impl->zap.reset();
      impl->context.reset();
      throw;
    }
  }
  std::promise<std::string> bound;
  std::future<std::string> endpoint = bound.get_future();
  impl->thread =
      std::thread([impl, promise = std::move(bound)]() mutable { impl->Run(std::move(promise)); });
  try {
    return endpoint.get();
  } catch (...) {
    StopSocketThread(impl);
    throw;
  }
}

}  // namespace kapfix::link
