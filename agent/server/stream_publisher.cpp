#include "agent/server/stream_publisher.hpp"

#include <google/protobuf/descriptor.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <zmq.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <deque>
#include <exception>
#include <future>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <utility>
#include <zmq.hpp>

#include "agent/server/intake_binding.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/heartbeat.pb.h"
#include "link/connection_monitor.hpp"
#include "link/link_endpoint.hpp"
#include "link/socket_thread_start.hpp"
#include "link/topic_names.hpp"
#include "link/topic_table.hpp"

namespace kapfix::agent {
namespace {

using google::protobuf::Message;
using kapfix::link::ConnectionMonitor;
using kapfix::link::ConnectionMonitorOptions;
using kapfix::link::RequireCurve;
using kapfix::link::StartSocketThread;
using kapfix::link::StopSocketThread;
using kapfix::link::ZapHandler;
using Clock = std::chrono::steady_clock;

using kapfix::link::kHeartbeatTopic;
using kapfix::link::kTelemetryTopic;
using kapfix::link::kVideoTopic;

// How long to wait before retrying a message ZeroMQ could not take (a subscriber's queue is at
// its high-water mark): short, so telemetry catches up as soon as the link drains.
constexpr auto kRetryDelay = std::chrono::milliseconds(1);

// The header of a link message (`Header header = 1;`), or nullptr for any other message.
kapfix::v1::Header* MutableHeader(Message& message) {
  const auto* field = message.GetDescriptor()->FindFieldByNumber(1);
  if (field == nullptr || field->message_type() == nullptr ||
      field->message_type()->full_name() != kapfix::v1::Header::descriptor()->full_name()) {
    return nullptr;
  }
  // A generated message's header is a generated Header; a DynamicMessage's is not, and is
  // refused (nullptr) rather than stamped through reflection.
  return dynamic_cast<kapfix::v1::Header*>(
      message.GetReflection()->MutableMessage(&message, field));
}

// [ms] the longest the publisher thread waits before reading subscriptions (XPUB_MANUAL: they
// wait in the socket until read, and a station's stream starts only once one is applied).
constexpr auto kSubscriptionPoll = std::chrono::milliseconds(10);
// [s] at most one log line per period about refused subscriptions.
constexpr auto kRefusalLogPeriod = std::chrono::seconds(10);

// A subscriber's connection, named by libzmq's descriptor and the address of its peer
// (getpeername's bytes): a descriptor reused by a later connection gets another name.
std::string ConnectionName(int fd) {
  sockaddr_storage address{};
  socklen_t size = sizeof address;
  if (fd < 0 || ::getpeername(fd, reinterpret_cast<sockaddr*>(&address), &size) != 0) return {};
  return std::to_string(fd) + "/" +
         std::string(reinterpret_cast<const char*>(&address),
                     std::min<std::size_t>(size, sizeof address));
}

bool StillConnected(const std::string& name) {
  const std::size_t slash = name.find('/');
  if (slash == std::string::npos) return false;
  return ConnectionName(std::atoi(name.substr(0, slash).c_str())) == name;
}

struct Pending {
  std::string topic;
  std::unique_ptr<Message> message;
  std::size_t bytes = 0;  // [bytes] serialized size when queued
};

}  // namespace

struct StreamPublisher::Impl {
  explicit Impl(StreamPublisherOptions opts)
      : options(std::move(opts)),
        video_min_interval(options.video_min_interval),
        book(options.subscriptions, StillConnected) {}

  void Run(std::promise<std::string> bound);
  void Loop(zmq::socket_t& socket);
  // Stamps and sends; false when ZeroMQ cannot take it now (high-water mark).
  bool Send(zmq::socket_t& socket, const std::string& topic, Message& message);
  void SendHeartbeat(zmq::socket_t& socket);
  // Reads every subscription waiting and applies those the book admits.
  void ReceiveSubscriptions(zmq::socket_t& socket);

  const StreamPublisherOptions options;

  std::mutex mutex;  // guards the members up to `stopping`
  std::condition_variable wake;
  std::deque<Pending> queue;
  std::size_t queued_bytes = 0;
  std::unique_ptr<Message> latest_video;
  std::chrono::microseconds video_min_interval;
  bool stopping = false;

  std::unique_ptr<zmq::context_t> context;
  std::unique_ptr<ZapHandler> zap;             // with CurveZMQ keys only
  std::unique_ptr<ConnectionMonitor> monitor;  // made by the socket thread
  IntakeBinding binding;                       // bound by the socket thread
  std::thread thread;

  std::atomic<std::uint64_t> telemetry_sent{0};
  std::atomic<std::uint64_t> telemetry_dropped{0};
  std::atomic<std::uint64_t> video_sent{0};
  std::atomic<std::uint64_t> video_dropped{0};
  std::atomic<std::uint64_t> other_sent{0};
  std::atomic<std::uint64_t> other_dropped{0};
  std::atomic<std::uint64_t> heartbeats_sent{0};
  std::atomic<std::uint64_t> rejected{0};

  // Publisher thread only.
  std::unordered_map<std::string, std::uint64_t> sequences;  // last sent, per topic
  Clock::time_point last_video_sent{};
  SubscriptionBook book;
  Clock::time_point last_refusal_logged{};
  std::uint64_t refusals_not_logged = 0;
  std::atomic<std::uint64_t> subscriptions_admitted{0};
  std::atomic<std::uint64_t> subscriptions_refused{0};
};

void StreamPublisher::Impl::Run(std::promise<std::string> bound) {
  std::optional<zmq::socket_t> socket;
  try {
    socket.emplace(*context, zmq::socket_type::xpub);
    socket->set(zmq::sockopt::linger, 0);
    // Subscriptions come to the publisher thread, which applies the ones it admits.
    socket->set(zmq::sockopt::xpub_manual, 1);
    // No XPUB_NODROP: with it, one subscriber that never reads stops the stream for all.
    // Without it, a full subscriber queue drops that subscriber's copy only.
    socket->set(zmq::sockopt::sndhwm, options.send_high_water_mark);
    // Subscriptions are messages from the peer: bounded like any other (issue 15, item 1).
    socket->set(zmq::sockopt::maxmsgsize, options.max_subscription_bytes);
    socket->set(zmq::sockopt::handshake_ivl, static_cast<int>(options.handshake_timeout.count()));
    socket->set(zmq::sockopt::heartbeat_ivl,
                static_cast<int>(options.zmtp_heartbeat_interval.count()));
    socket->set(zmq::sockopt::heartbeat_timeout,
                static_cast<int>(options.zmtp_heartbeat_timeout.count()));
    if (options.curve) RequireCurve(*socket, *options.curve);
    std::string why;
    const std::optional<link::LinkEndpoint> endpoint =
        link::ParseLinkEndpoint(options.bind_endpoint, &why);
    if (!endpoint) {
      bound.set_exception(std::make_exception_ptr(std::runtime_error("stream publisher: " + why)));
      return;
    }
    const bool behind_intake = options.intake && endpoint->canonical.rfind("tcp://", 0) == 0;
    // Behind an intake the intake keeps the connection budget (CommandServer::Impl::Run).
    monitor = std::make_unique<ConnectionMonitor>(
        "stream publisher",
        ConnectionMonitorOptions{.max_connections =
                                     behind_intake ? SIZE_MAX : options.max_connections});
    monitor->Start(*context, *socket);
    bound.set_value(binding.Bind(*socket, *endpoint, options.intake, options.max_connections,
                                 "stream publisher"));
  } catch (const std::runtime_error& error) {
    bound.set_exception(std::make_exception_ptr(std::runtime_error(
        "stream publisher cannot bind '" + options.bind_endpoint + "': " + error.what())));
    return;
  } catch (const zmq::error_t& error) {
    bound.set_exception(std::make_exception_ptr(std::runtime_error(
        "stream publisher cannot bind '" + options.bind_endpoint + "': " + error.what())));
    return;
  }
  try {
    Loop(*socket);
  } catch (const zmq::error_t&) {
    // ETERM: Stop() shut the context down while a send was in progress.
  }
}

void StreamPublisher::Impl::Loop(zmq::socket_t& socket) {
  Clock::time_point next_heartbeat = Clock::now();
  Clock::time_point retry_at{};  // queue paused until then after ZeroMQ refused a message
  while (true) {
    std::optional<Pending> item;
    std::unique_ptr<Message> video;
    {
      std::unique_lock lock(mutex);
      const auto video_due = [&] { return last_video_sent + video_min_interval; };
      const auto ready = [&] {
        const auto now = Clock::now();
        return stopping || (!queue.empty() && now >= retry_at) ||
               (latest_video != nullptr && now >= video_due());
      };
      Clock::time_point until = std::min(next_heartbeat, Clock::now() + kSubscriptionPoll);
      if (!queue.empty()) until = std::min(until, retry_at);
      if (latest_video != nullptr) until = std::min(until, video_due());
      wake.wait_until(lock, until, ready);
      if (stopping) return;
      const auto now = Clock::now();
      if (!queue.empty() && now >= retry_at) {
        item = std::move(queue.front());
        queue.pop_front();
        queued_bytes -= item->bytes;
      }
      if (latest_video != nullptr && now >= video_due()) video = std::move(latest_video);
    }
    ReceiveSubscriptions(socket);
    if (item) {
      if (Send(socket, item->topic, *item->message)) {
        (item->topic == kTelemetryTopic ? telemetry_sent : other_sent).fetch_add(1);
      } else {
        // Back to the head of the queue, order kept; retried after a short pause.
        const std::lock_guard lock(mutex);
        queued_bytes += item->bytes;
        queue.push_front(std::move(*item));
        retry_at = Clock::now() + kRetryDelay;
      }
    }
    if (video) {
      if (Send(socket, std::string(kVideoTopic), *video)) {
        video_sent.fetch_add(1);
        last_video_sent = Clock::now();
      } else {
        video_dropped.fetch_add(1);  // stale by the time ZeroMQ could take it: not retried
      }
    }
    if (Clock::now() >= next_heartbeat) {
      SendHeartbeat(socket);
      next_heartbeat = std::max(next_heartbeat + options.heartbeat_interval,
                                Clock::now() + options.heartbeat_interval / 2);
    }
  }
}

bool StreamPublisher::Impl::Send(zmq::socket_t& socket, const std::string& topic,
                                 Message& message) {
  const std::uint64_t sequence = sequences[topic] + 1;
  kapfix::v1::Stamp(MutableHeader(message), options.agent_id, sequence, options.boot_id);
  const std::string bytes = message.SerializeAsString();
  if (!socket.send(zmq::buffer(topic), zmq::send_flags::sndmore | zmq::send_flags::dontwait)) {
    return false;
  }
  // The first part went: the rest of the message must follow (and is accepted, as the
  // high-water mark counts whole messages). Blocking here is therefore at most momentary.
  (void)socket.send(zmq::buffer(bytes), zmq::send_flags::none);
  sequences[topic] = sequence;
  return true;
}

void StreamPublisher::Impl::ReceiveSubscriptions(zmq::socket_t& socket) {
  while (true) {
    zmq::message_t message;
    if (!socket.recv(message, zmq::recv_flags::dontwait)) return;
    const int fd = zmq_msg_get(message.handle(), ZMQ_SRCFD);
    // Counted as the longer of its two wire forms (a ZMTP 3.1 SUBSCRIBE command adds 9 bytes
    // to a 3.0 subscription message); an intake never credits more than it relayed.
    link::ReceivedWire wire{.curve = options.curve.has_value(), .source_fd = fd};
    wire.bytes = link::ZmtpWireBytes(message.size() + 9, wire.curve);
    bool more = message.more();
    while (more) {  // anything else a subscriber sends: read, counted and dropped
      zmq::message_t rest;
      if (!socket.recv(rest, zmq::recv_flags::dontwait)) break;
      wire.bytes += link::ZmtpWireBytes(rest.size(), wire.curve);
      more = rest.more();
    }
    binding.Consumed(wire);
    const SubscriptionBook::Decision decision =
        book.Receive(ConnectionName(fd), message.to_string_view());
    if (decision.action == SubscriptionBook::Action::kSubscribe) {
      socket.set(zmq::sockopt::subscribe, decision.topic);  // for the pipe it came from
      subscriptions_admitted.fetch_add(1);
    } else if (decision.action == SubscriptionBook::Action::kUnsubscribe) {
      socket.set(zmq::sockopt::unsubscribe, decision.topic);
    } else if (!decision.refusal.empty()) {
      // libzmq keeps every subscription it reads in a trie of its own for the connection
      // (XPUB_MANUAL too), whether applied or not: only ending the connection frees it. A
      // station never sends what the book refuses.
      binding.Disconnect(fd);
      subscriptions_refused.fetch_add(1);
      const auto now = Clock::now();
      if (now - last_refusal_logged >= kRefusalLogPeriod) {
        const std::string address = binding.PeerAddressOf(fd);
        spdlog::warn("stream publisher: closed a subscriber for {}{}{}", decision.refusal,
                     address.empty() ? std::string() : " from " + address,
                     refusals_not_logged == 0 ? std::string()
                                              : " (and " + std::to_string(refusals_not_logged) +
                                                    " other subscriptions since the last line)");
        last_refusal_logged = now;
        refusals_not_logged = 0;
      } else {
        ++refusals_not_logged;
      }
    }
  }
}

void StreamPublisher::Impl::SendHeartbeat(zmq::socket_t& socket) {
  kapfix::v1::Heartbeat heartbeat;
  heartbeat.set_interval_ms(static_cast<std::uint32_t>(options.heartbeat_interval.count()));
  // Every message named here has been through Send(), i.e. written whole to each
  // subscriber's pipe or dropped for it, before this heartbeat follows it down the same pipes:
  // a subscriber that reads this and has not read one of them never will (StreamLossCounter).
  for (const auto& [topic, newest] : sequences) {
    if (topic == kHeartbeatTopic) continue;  // the heartbeat's own header numbers that topic
    kapfix::v1::TopicCount* count = heartbeat.add_newest_sequence();
    count->set_topic(topic);
    count->set_count(newest);
  }
  // The round trip is measured on the command socket (CommandServer echoes each station's
  // heartbeat): a PUB message reaches every station, so it cannot echo one of them.
  if (Send(socket, std::string(kHeartbeatTopic), heartbeat)) heartbeats_sent.fetch_add(1);
}

StreamPublisher::StreamPublisher(StreamPublisherOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}

StreamPublisher::~StreamPublisher() { Stop(); }

std::string StreamPublisher::Start() {
  if (impl_->thread.joinable()) throw std::runtime_error("stream publisher already started");
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->stopping = false;
  }
  return StartSocketThread(impl_.get(), "stream publisher");
}

void StreamPublisher::Stop() {
  if (!impl_->thread.joinable()) return;
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->stopping = true;
    impl_->queue.clear();
    impl_->queued_bytes = 0;
    impl_->latest_video.reset();
  }
  impl_->wake.notify_all();
  StopSocketThread(impl_.get());  // a send blocked inside ZeroMQ returns with ETERM
  impl_->binding.Close();
}

bool StreamPublisher::Publish(const Message& message) {
  std::string topic = kapfix::link::TopicFor(message);
  if (topic.empty() || topic == kapfix::link::kCommandTopic) {
    impl_->rejected.fetch_add(1);
    return false;
  }
  std::unique_ptr<Message> copy(message.New());
  copy->CopyFrom(message);
  if (MutableHeader(*copy) == nullptr) {
    impl_->rejected.fetch_add(1);
    return false;
  }
  if (topic == kVideoTopic) {
    {
      const std::lock_guard lock(impl_->mutex);
      if (impl_->latest_video != nullptr) impl_->video_dropped.fetch_add(1);
      impl_->latest_video = std::move(copy);
    }
    impl_->wake.notify_one();
    return true;
  }
  const std::size_t bytes = copy->ByteSizeLong();
  {
    const std::lock_guard lock(impl_->mutex);
    if (impl_->queue.size() >= impl_->options.queue_messages ||
        impl_->queued_bytes + bytes > impl_->options.queue_bytes) {
      (topic == kTelemetryTopic ? impl_->telemetry_dropped : impl_->other_dropped).fetch_add(1);
      return false;
    }
    impl_->queued_bytes += bytes;
    impl_->queue.push_back(Pending{std::move(topic), std::move(copy), bytes});
  }
  impl_->wake.notify_one();
  return true;
}

void StreamPublisher::SetVideoMinInterval(std::chrono::microseconds interval) {
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->video_min_interval = std::max(interval, std::chrono::microseconds(0));
  }
  impl_->wake.notify_one();
}

StreamPublisher::Counters StreamPublisher::counters() const {
  Counters counters;
  counters.telemetry_sent = impl_->telemetry_sent.load();
  counters.telemetry_dropped = impl_->telemetry_dropped.load();
  counters.video_sent = impl_->video_sent.load();
  counters.video_dropped = impl_->video_dropped.load();
  counters.other_sent = impl_->other_sent.load();
  counters.other_dropped = impl_->other_dropped.load();
  counters.heartbeats_sent = impl_->heartbeats_sent.load();
  counters.rejected = impl_->rejected.load();
  counters.subscriptions_admitted = impl_->subscriptions_admitted.load();
  counters.subscriptions_refused = impl_->subscriptions_refused.load();
  const link::BoundedIntake::Counters intake = impl_->binding.counters();
  counters.intake_paused = intake.paused;
  counters.intake_closed = intake.closed_over_budget;
  return counters;
}

}  // namespace kapfix::agent
