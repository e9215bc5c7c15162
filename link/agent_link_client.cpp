#include "link/agent_link_client.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <future>
#include <iterator>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/heartbeat.pb.h"
#include "link/envelope.hpp"
#include "link/handshake_monitor.hpp"
#include "link/stream_loss_counter.hpp"
#include "link/topic_names.hpp"
#include "link/topic_table.hpp"
#include "link/wake_signal.hpp"

namespace kapfix::link {
namespace {

using Clock = std::chrono::steady_clock;
using kapfix::v1::Command;
using kapfix::v1::Reply;

// At most this many messages per socket per loop turn, so that a flood of video cannot
// starve requests, timers and the other socket.
constexpr int kBurst = 256;
// Longest sleep of the I/O thread when nothing is due; while a command waits for the
// connection (ZMQ_IMMEDIATE refuses it until then), retry this often.
constexpr auto kIdlePoll = std::chrono::milliseconds(250);
constexpr auto kUnsentRetry = std::chrono::milliseconds(5);

struct Outgoing {
  Command command;
  Clock::time_point deadline;
  AgentLinkClient::ReplyHandler done;
};

struct Waiting {
  Clock::time_point deadline;
  AgentLinkClient::ReplyHandler done;
};

// [delimiter, topic, bytes] on the DEALER: the delimiter keeps the envelope REQ-compatible.
// False when ZeroMQ cannot take it now (not connected: ZMQ_IMMEDIATE).
bool SendRequest(zmq::socket_t& dealer, std::string_view topic, const std::string& bytes) {
  if (!dealer.send(zmq::message_t(), zmq::send_flags::sndmore | zmq::send_flags::dontwait)) {
    return false;
  }
  // Once the first part is taken the rest of the message goes to the same pipe, whose
  // high-water mark counts whole messages: these do not block.
  (void)dealer.send(zmq::buffer(topic), zmq::send_flags::sndmore);
  (void)dealer.send(zmq::buffer(bytes), zmq::send_flags::none);
  return true;
}

const kapfix::v1::Header* HeaderOf(const google::protobuf::Message& message) {
  const auto* field = message.GetDescriptor()->FindFieldByNumber(1);
  if (field == nullptr || field->message_type() == nullptr) return nullptr;
  return dynamic_cast<const kapfix::v1::Header*>(
      &message.GetReflection()->GetMessage(message, field));
}

}  // namespace

struct AgentLinkClient::Impl {
  explicit Impl(AgentLinkClientOptions opts) : options(std::move(opts)) {}

  void Run(std::promise<void> started);
  void Loop(zmq::socket_t& dealer, zmq::socket_t& sub);
  Clock::time_point NextWake(Clock::time_point next_heartbeat) const;
  void ReceiveReplies(zmq::socket_t& dealer);
  void ReceiveStreams(zmq::socket_t& sub);
  void HandleStream(std::string_view topic, std::string_view payload);
  void SendOutgoing(zmq::socket_t& dealer);
  void Expire();
  void SendHeartbeat(zmq::socket_t& dealer);
  void Heard(const std::string& agent_id);
  void NoteHandshakes();
  void UpdateLink();
  bool LinkUp(const LinkStatus& status) const;

  const AgentLinkClientOptions options;
  std::map<std::string, MessageHandler, std::less<>> handlers;
  RawHandler raw_handler;
  LinkHandler link_handler;
  WakeSignal wake;

  std::mutex mutex;  // guards queued, stopping, running
  std::deque<Outgoing> queued;
  bool stopping = false;
  bool running = false;

  mutable std::mutex status_mutex;  // guards status, losses, streams_heard
  std::condition_variable streams_arrived;
  LinkStatus status;
  StreamLossCounter losses;  // status.sequence_gaps is its total
  bool streams_heard = false;

  std::unique_ptr<zmq::context_t> context;
  std::thread thread;
  std::atomic<std::thread::id> io_thread_id{};
  std::optional<HandshakeMonitor> command_handshakes;  // I/O thread only
  std::optional<HandshakeMonitor> stream_handshakes;

  // I/O thread only (and Stop(), after joining it).
  std::deque<Outgoing> unsent;
  std::unordered_map<std::uint64_t, Waiting> waiting;  // by command sequence
  std::uint64_t command_sequence = 0;
  std::uint64_t heartbeat_sequence = 0;
  bool reported_up = false;
};

void AgentLinkClient::Impl::Run(std::promise<void> started) {
  io_thread_id.store(std::this_thread::get_id());
  std::optional<zmq::socket_t> dealer;
  std::optional<zmq::socket_t> sub;
  try {
    dealer.emplace(*context, zmq::socket_type::dealer);
    sub.emplace(*context, zmq::socket_type::sub);
    for (zmq::socket_t* socket : {&*dealer, &*sub}) {
      socket->set(zmq::sockopt::linger, 0);
      socket->set(zmq::sockopt::maxmsgsize,
                  static_cast<std::int64_t>(kapfix::v1::kMaxMessageBytes));
      socket->set(zmq::sockopt::heartbeat_ivl,
                  static_cast<int>(options.zmtp_heartbeat_interval.count()));
      socket->set(zmq::sockopt::heartbeat_timeout,
                  static_cast<int>(options.zmtp_heartbeat_timeout.count()));
    }
    // Queue commands only on a live connection: one sent while the agent is away would
    // otherwise wait in ZeroMQ and reach the servos long after its requester gave up.
    dealer->set(zmq::sockopt::immediate, true);
    sub->set(zmq::sockopt::rcvhwm, options.stream_receive_high_water_mark);
    if (raw_handler) {
      sub->set(zmq::sockopt::subscribe, "");
    } else {
      sub->set(zmq::sockopt::subscribe, kHeartbeatTopic);
      for (const auto& [topic, handler] : handlers) sub->set(zmq::sockopt::subscribe, topic);
    }
    if (options.curve) {
      for (zmq::socket_t* socket : {&*dealer, &*sub}) {
        socket->set(zmq::sockopt::curve_serverkey, options.curve->agent_public_key);
        socket->set(zmq::sockopt::curve_publickey, options.curve->station.public_key);
        socket->set(zmq::sockopt::curve_secretkey, options.curve->station.secret_key);
      }
    }
    // Before connecting, so that no handshake goes unwatched; destroyed before the sockets.
    command_handshakes.emplace(*dealer, "command");
    stream_handshakes.emplace(*sub, "stream");
    dealer->connect(options.command_endpoint);
    sub->connect(options.stream_endpoint);
  } catch (const zmq::error_t& error) {
    command_handshakes.reset();
    stream_handshakes.reset();
    started.set_exception(std::make_exception_ptr(
        std::runtime_error("cannot connect to '" + options.command_endpoint + "' / '" +
                           options.stream_endpoint + "': " + error.what())));
    return;
  }
  started.set_value();
  Loop(*dealer, *sub);
  command_handshakes.reset();
  stream_handshakes.reset();
}

void AgentLinkClient::Impl::Loop(zmq::socket_t& dealer, zmq::socket_t& sub) {
  Clock::time_point next_heartbeat = Clock::now();
  while (true) {
    std::array<zmq_pollitem_t, 3> items{{
        {dealer.handle(), 0, ZMQ_POLLIN, 0},
        {sub.handle(), 0, ZMQ_POLLIN, 0},
        {nullptr, wake.fd(), ZMQ_POLLIN, 0},
    }};
    const auto wait =
        std::chrono::ceil<std::chrono::milliseconds>(NextWake(next_heartbeat) - Clock::now());
    try {
      zmq::poll(items, std::max(wait, std::chrono::milliseconds(0)));
    } catch (const zmq::error_t&) {
      continue;  // EINTR: a signal arrived (kapfix-ctl's Ctrl-C); look at the flags again
    }
    if ((items[2].revents & ZMQ_POLLIN) != 0) wake.Clear();
    {
      const std::lock_guard lock(mutex);
      if (stopping) return;
      while (!queued.empty()) {
        unsent.push_back(std::move(queued.front()));
        queued.pop_front();
      }
    }
    NoteHandshakes();
    ReceiveReplies(dealer);
    ReceiveStreams(sub);
    SendOutgoing(dealer);
    Expire();
    if (Clock::now() >= next_heartbeat) {
      SendHeartbeat(dealer);
      next_heartbeat = Clock::now() + options.heartbeat_interval;
    }
    UpdateLink();
  }
}

void AgentLinkClient::Impl::NoteHandshakes() {
  command_handshakes->Poll();
  stream_handshakes->Poll();
  const std::string& failure = !command_handshakes->failure().empty()
                                   ? command_handshakes->failure()
                                   : stream_handshakes->failure();
  const std::lock_guard lock(status_mutex);
  status.handshake_failure = failure;
}

Clock::time_point AgentLinkClient::Impl::NextWake(Clock::time_point next_heartbeat) const {
  Clock::time_point wake_at = std::min(next_heartbeat, Clock::now() + kIdlePoll);
  if (!unsent.empty()) wake_at = std::min(wake_at, Clock::now() + kUnsentRetry);
  for (const auto& [sequence, entry] : waiting) wake_at = std::min(wake_at, entry.deadline);
  return wake_at;
}

void AgentLinkClient::Impl::ReceiveReplies(zmq::socket_t& dealer) {
  for (int i = 0; i < kBurst; ++i) {
    std::vector<zmq::message_t> frames;
    if (!zmq::recv_multipart(dealer, std::back_inserter(frames), zmq::recv_flags::dontwait)) {
      return;
    }
    std::size_t next = 0;
    if (!frames.empty() && frames[0].size() == 0) ++next;  // the delimiter
    if (frames.size() != next + 2) continue;               // not an answer of ours
    const std::string_view topic = frames[next].to_string_view();
    const std::string_view payload = frames[next + 1].to_string_view();
    if (topic == kReplyTopic) {
      Reply reply;
      if (!kapfix::link::DecodeEnvelope(topic, payload, &reply, kapfix::v1::kMaxMessageBytes,
                                        nullptr)) {
        continue;
      }
      Heard(reply.header().agent_id());
      const auto it = waiting.find(reply.command_sequence());
      if (it == waiting.end()) continue;  // answered after its deadline: already reported
      ReplyHandler done = std::move(it->second.done);
      waiting.erase(it);
      done(std::move(reply));
    } else if (topic == kHeartbeatTopic) {
      kapfix::v1::Heartbeat echo;
      if (!kapfix::link::DecodeEnvelope(topic, payload, &echo, kapfix::v1::kMaxMessageBytes,
                                        nullptr)) {
        continue;
      }
      Heard(echo.header().agent_id());
      if (echo.echoed_sequence() == 0 || echo.echoed_sequence() > heartbeat_sequence) continue;
      const std::int64_t latency =
          kapfix::v1::NowMicros() - echo.echoed_send_time_us() - echo.echo_hold_us();
      const std::lock_guard lock(status_mutex);
      status.latency_us = std::max<std::int64_t>(latency, 0);
    }
  }
}

void AgentLinkClient::Impl::ReceiveStreams(zmq::socket_t& sub) {
  for (int i = 0; i < kBurst; ++i) {
    std::vector<zmq::message_t> frames;
    if (!zmq::recv_multipart(sub, std::back_inserter(frames), zmq::recv_flags::dontwait)) {
      return;
    }
    if (frames.size() != 2) {
      const std::lock_guard lock(status_mutex);
      ++status.messages_invalid;
      continue;
    }
    HandleStream(frames[0].to_string_view(), frames[1].to_string_view());
  }
}

void AgentLinkClient::Impl::HandleStream(std::string_view topic, std::string_view payload) {
  if (raw_handler) raw_handler(topic, payload);
  std::unique_ptr<google::protobuf::Message> message = kapfix::link::NewMessageForTopic(topic);
  const kapfix::v1::Header* header = nullptr;
  if (message != nullptr && kapfix::link::DecodeEnvelope(topic, payload, message.get(),
                                                         kapfix::v1::kMaxMessageBytes, nullptr)) {
    header = HeaderOf(*message);
  }
  if (header == nullptr) {
    const std::lock_guard lock(status_mutex);
    ++status.messages_invalid;
    return;
  }
  Heard(header->agent_id());
  {
    const std::lock_guard lock(status_mutex);
    ++status.messages_received;
    losses.Received(topic, *header);
    // The agent's heartbeat names the newest message of each topic: one not received by now
    // is lost (StreamLossCounter says why it cannot still be on its way).
    const auto* beat = dynamic_cast<const kapfix::v1::Heartbeat*>(message.get());
    if (topic == kHeartbeatTopic && beat != nullptr) losses.Heard(*beat);
    status.sequence_gaps = losses.total();
    streams_heard = true;
  }
  streams_arrived.notify_all();
  const auto it = handlers.find(topic);
  if (it != handlers.end()) it->second(*message);
}

void AgentLinkClient::Impl::SendOutgoing(zmq::socket_t& dealer) {
  while (!unsent.empty()) {
    Outgoing& next = unsent.front();
    if (Clock::now() >= next.deadline) {
      ReplyHandler done = std::move(next.done);
      unsent.pop_front();
      done(std::nullopt);  // never sent: nobody waits for it any more
      continue;
    }
    next.command.clear_header();
    kapfix::v1::Stamp(next.command.mutable_header(), options.agent_id, command_sequence + 1);
    if (!SendRequest(dealer, kCommandTopic, next.command.SerializeAsString())) return;
    ++command_sequence;
    waiting.emplace(command_sequence, Waiting{next.deadline, std::move(next.done)});
    unsent.pop_front();
  }
}

void AgentLinkClient::Impl::Expire() {
  const auto now = Clock::now();
  for (auto it = waiting.begin(); it != waiting.end();) {
    if (now < it->second.deadline) {
      ++it;
      continue;
    }
    ReplyHandler done = std::move(it->second.done);
    it = waiting.erase(it);
    done(std::nullopt);
  }
}

void AgentLinkClient::Impl::SendHeartbeat(zmq::socket_t& dealer) {
  kapfix::v1::Heartbeat heartbeat;
  kapfix::v1::Stamp(heartbeat.mutable_header(), options.agent_id, ++heartbeat_sequence);
  heartbeat.set_interval_ms(static_cast<std::uint32_t>(options.heartbeat_interval.count()));
  {
    const std::lock_guard lock(status_mutex);
    losses.FillLost(&heartbeat);  // the agent counts each station's losses from these
  }
  // Not connected: dropped, as a stale heartbeat would only fake a latency.
  (void)SendRequest(dealer, kHeartbeatTopic, heartbeat.SerializeAsString());
}

void AgentLinkClient::Impl::Heard(const std::string& agent_id) {
  const std::lock_guard lock(status_mutex);
  status.last_heard_us = kapfix::v1::NowMicros();
  status.agent_id = agent_id;
}

bool AgentLinkClient::Impl::LinkUp(const LinkStatus& current) const {
  const auto timeout_us =
      std::chrono::duration_cast<std::chrono::microseconds>(options.link_timeout).count();
  return current.last_heard_us != 0 && kapfix::v1::NowMicros() - current.last_heard_us < timeout_us;
}

void AgentLinkClient::Impl::UpdateLink() {
  bool up = false;
  {
    const std::lock_guard lock(status_mutex);
    up = LinkUp(status);
  }
  if (up == reported_up) return;
  reported_up = up;
  if (link_handler) link_handler(up);
}

AgentLinkClient::AgentLinkClient(AgentLinkClientOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}

AgentLinkClient::~AgentLinkClient() { Stop(); }

void AgentLinkClient::OnMessage(const std::string& topic, MessageHandler handler) {
  if (impl_->thread.joinable()) throw std::logic_error("OnMessage() after Start()");
  impl_->handlers[topic] = std::move(handler);
}

void AgentLinkClient::OnRawMessage(RawHandler handler) {
  if (impl_->thread.joinable()) throw std::logic_error("OnRawMessage() after Start()");
  impl_->raw_handler = std::move(handler);
}

void AgentLinkClient::OnLinkChange(LinkHandler handler) {
  if (impl_->thread.joinable()) throw std::logic_error("OnLinkChange() after Start()");
  impl_->link_handler = std::move(handler);
}

void AgentLinkClient::Start() {
  if (impl_->thread.joinable()) throw std::runtime_error("link client already started");
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->stopping = false;
    impl_->running = true;
  }
  {
    const std::lock_guard lock(impl_->status_mutex);
    impl_->streams_heard = false;
  }
  impl_->context = std::make_unique<zmq::context_t>(1);
  std::promise<void> started;
  std::future<void> connected = started.get_future();
  impl_->thread = std::thread([impl = impl_.get(), promise = std::move(started)]() mutable {
    impl->Run(std::move(promise));
  });
  try {
    connected.get();
  } catch (...) {
    impl_->thread.join();
    impl_->context.reset();
    const std::lock_guard lock(impl_->mutex);
    impl_->running = false;
    throw;
  }
}

void AgentLinkClient::Stop() {
  if (!impl_->thread.joinable()) return;
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->stopping = true;
    impl_->running = false;
  }
  impl_->wake.Notify();
  impl_->thread.join();
  impl_->context.reset();
  impl_->io_thread_id.store(std::thread::id());
  // Every request gets its answer, even the ones the I/O thread never saw.
  std::vector<ReplyHandler> pending;
  {
    const std::lock_guard lock(impl_->mutex);
    for (Outgoing& entry : impl_->queued) pending.push_back(std::move(entry.done));
    impl_->queued.clear();
  }
  for (Outgoing& entry : impl_->unsent) pending.push_back(std::move(entry.done));
  impl_->unsent.clear();
  for (auto& [sequence, entry] : impl_->waiting) pending.push_back(std::move(entry.done));
  impl_->waiting.clear();
  for (ReplyHandler& done : pending) done(std::nullopt);
}

std::optional<Reply> AgentLinkClient::Request(Command command, std::chrono::milliseconds timeout) {
  if (std::this_thread::get_id() == impl_->io_thread_id.load()) {
    throw std::logic_error("AgentLinkClient::Request() from a handler would wait for itself");
  }
  auto answer = std::make_shared<std::promise<std::optional<Reply>>>();
  std::future<std::optional<Reply>> reply = answer->get_future();
  RequestAsync(std::move(command), timeout,
               [answer](std::optional<Reply> result) { answer->set_value(std::move(result)); });
  return reply.get();  // `done` always runs: reply, deadline, or Stop()
}

void AgentLinkClient::RequestAsync(Command command, std::chrono::milliseconds timeout,
                                   ReplyHandler done) {
  {
    const std::lock_guard lock(impl_->mutex);
    if (impl_->running && !impl_->stopping) {
      impl_->queued.push_back(
          Outgoing{std::move(command), Clock::now() + timeout, std::move(done)});
      done = nullptr;
    }
  }
  if (done) {
    done(std::nullopt);
    return;
  }
  impl_->wake.Notify();
}

bool AgentLinkClient::WaitForStreams(std::chrono::milliseconds timeout) {
  std::unique_lock lock(impl_->status_mutex);
  return impl_->streams_arrived.wait_for(lock, timeout, [this] { return impl_->streams_heard; });
}

std::uint64_t AgentLinkClient::SequenceGaps(std::string_view topic) const {
  const std::lock_guard lock(impl_->status_mutex);
  return impl_->losses.Lost(topic);
}

LinkStatus AgentLinkClient::Status() const {
  const std::lock_guard lock(impl_->status_mutex);
  LinkStatus copy = impl_->status;
  copy.up = impl_->LinkUp(copy);
  return copy;
}

}  // namespace kapfix::link
