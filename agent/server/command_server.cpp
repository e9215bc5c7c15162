#include "agent/server/command_server.hpp"

#include <google/protobuf/io/coded_stream.h>
#include <google/protobuf/wire_format_lite.h>
#include <spdlog/spdlog.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <exception>
#include <future>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>
#include <zmq.hpp>

#include "agent/server/command_intake.hpp"
#include "agent/server/intake_binding.hpp"
#include "kapfix/v1/heartbeat.pb.h"
#include "link/connection_monitor.hpp"
#include "link/envelope.hpp"
#include "link/link_endpoint.hpp"
#include "link/request_frames.hpp"
#include "link/socket_thread_start.hpp"
#include "link/topic_names.hpp"
#include "link/whole_message_receive.hpp"

namespace kapfix::agent {
namespace {

using kapfix::link::ConnectionMonitor;
using kapfix::link::ConnectionMonitorOptions;
using kapfix::link::kRequestFramesKept;
using kapfix::link::ParseRequestFrames;
using kapfix::link::RequestFrames;
using kapfix::link::RequireCurve;
using kapfix::link::StartSocketThread;
using kapfix::link::StopSocketThread;
using kapfix::link::ZapHandler;
using kapfix::v1::Reply;

// A request has at most routing id, delimiter, topic and message; anything longer is
// malformed, and its extra frames are read and discarded rather than kept in memory.
constexpr std::size_t kMaxFramesKept = 1 + kRequestFramesKept;

using kapfix::link::kHeartbeatTopic;
using kapfix::link::kReplyTopic;

std::string_view View(const zmq::message_t& frame) { return frame.to_string_view(); }

// The station across connections: with CurveZMQ, the name (or key) the ZAP handler gave its
// key; a plain station has none that it could not choose itself.
std::string StationOf(const zmq::message_t& frame) {
  const char* user = zmq_msg_gets(frame.handle(), "User-Id");
  return user != nullptr ? std::string(user) : std::string();
}

// One request as it arrived: the frames kept and how many there were in all.
struct Request {
  std::vector<zmq::message_t> frames;
  std::size_t frame_count = 0;
  std::int64_t received_us = 0;  // [µs since epoch]
  int source_fd = -1;            // libzmq's descriptor of its connection (ZMQ_SRCFD)
};

// header.sequence of a serialized Command, reading its header field only (a refusal before
// decoding still names the command it answers); 0 when there is none or it does not parse.
std::uint64_t CommandSequenceOf(std::string_view payload) {
  using google::protobuf::internal::WireFormatLite;
  google::protobuf::io::CodedInputStream input(
      reinterpret_cast<const std::uint8_t*>(payload.data()), static_cast<int>(payload.size()));
  constexpr int kHeaderField = kapfix::v1::Command::kHeaderFieldNumber;
  std::uint64_t sequence = 0;
  while (const std::uint32_t tag = input.ReadTag()) {
    if (WireFormatLite::GetTagFieldNumber(tag) == kHeaderField &&
        WireFormatLite::GetTagWireType(tag) == WireFormatLite::WIRETYPE_LENGTH_DELIMITED) {
      std::uint32_t size = 0;
      std::string bytes;
      kapfix::v1::Header header;
      if (!input.ReadVarint32(&size) || !input.ReadString(&bytes, static_cast<int>(size)) ||
          !header.ParseFromString(bytes)) {
        return 0;
      }
      sequence = header.sequence();  // the last one wins, as protobuf's merge has it
    } else if (!WireFormatLite::SkipField(&input, tag)) {
      return 0;
    }
  }
  return sequence;
}

// What a request's frames say, and how to address the answer.
struct Envelope {
  bool delimiter = false;            // an empty frame followed the routing id
  std::optional<std::string> topic;  // the topic frame, if one was sent
  std::string_view payload;
};

}  // namespace

struct CommandServer::Impl {
  Impl(AgentControl& agent, CommandServerOptions opts)
      : options(std::move(opts)),
        intake(agent, options.agent_id, options.limits, options.replay),
        subscriber_losses(options.subscriber_losses) {
    if (options.rate_limit) rate_limit.emplace(*options.rate_limit);
  }

  void Run(std::promise<std::string> bound);
  void Serve(zmq::socket_t& socket);
  void Handle(zmq::socket_t& socket, const Request& request);
  void HandleCommand(zmq::socket_t& socket, const Request& request, const Envelope& envelope);
  bool RateLimited(zmq::socket_t& socket, const Request& request, const Envelope& envelope);
  std::string RateKey(const Request& request) const;
  void HandleHeartbeat(zmq::socket_t& socket, const Request& request, const Envelope& envelope);
  std::string StationName(const Request& request) const;
  void SendReply(zmq::socket_t& socket, const Request& request, const Envelope& envelope,
                 Reply reply, std::uint64_t command_sequence);
  void Send(zmq::socket_t& socket, const Request& request, bool delimiter,
            std::optional<std::string_view> topic, const std::string& payload);

  const CommandServerOptions options;
  CommandIntake intake;  // owned by the server thread
  SubscriberLossBook subscriber_losses;
  std::optional<CommandRateLimit> rate_limit;  // owned by the server thread; unset: no limit

  std::unique_ptr<zmq::context_t> context;
  std::unique_ptr<ZapHandler> zap;             // with CurveZMQ keys only
  std::unique_ptr<ConnectionMonitor> monitor;  // made by the socket thread
  IntakeBinding binding;                       // bound by the socket thread
  std::thread thread;

  std::atomic<std::uint64_t> commands_ok{0};
  std::atomic<std::uint64_t> commands_refused{0};
  std::atomic<std::uint64_t> commands_rate_limited{0};
  std::atomic<std::uint64_t> heartbeats_echoed{0};
  std::atomic<std::uint64_t> heartbeats_ignored{0};
  std::atomic<std::int64_t> last_station_heard_us{0};

  // Owned by the server thread. Keyed by routing id (as the intake's command sequences are):
  // ROUTER gives each connection its own, so a station that reconnects starts a new
  // numbering, and no station can pose as another.
  kapfix::v1::SequenceGuard heartbeat_guard;
  std::uint64_t reply_sequence = 0;
  std::uint64_t heartbeat_sequence = 0;
};

void CommandServer::Impl::Run(std::promise<std::string> bound) {
  std::optional<zmq::socket_t> socket;
  try {
    socket.emplace(*context, zmq::socket_type::router);
    socket->set(zmq::sockopt::linger, 0);  // Stop() must not wait for replies to gone peers
    socket->set(zmq::sockopt::maxmsgsize, options.transport_limit_bytes);
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
      bound.set_exception(std::make_exception_ptr(std::runtime_error("command server: " + why)));
      return;
    }
    const bool behind_intake = options.intake && endpoint->canonical.rfind("tcp://", 0) == 0;
    // Behind an intake the socket sees only the intake's unix connections: the intake keeps
    // the connection budget, where the peers' TCP connections are.
    monitor = std::make_unique<ConnectionMonitor>(
        "command server",
        ConnectionMonitorOptions{.max_connections =
                                     behind_intake ? SIZE_MAX : options.max_connections});
    monitor->Start(*context, *socket);
    bound.set_value(binding.Bind(*socket, *endpoint, options.intake, options.max_connections,
                                 "command server"));
  } catch (const std::runtime_error& error) {
    bound.set_exception(std::make_exception_ptr(std::runtime_error(
        "command server cannot bind '" + options.bind_endpoint + "': " + error.what())));
    return;
  } catch (const zmq::error_t& error) {
    bound.set_exception(std::make_exception_ptr(std::runtime_error(
        "command server cannot bind '" + options.bind_endpoint + "': " + error.what())));
    return;
  }
  Serve(*socket);
}

void CommandServer::Impl::Serve(zmq::socket_t& socket) {
  while (true) {
    Request request;
    try {
      // Blocks; Stop() shuts the context down, which makes it throw ETERM.
      link::ReceivedWire wire{.curve = options.curve.has_value(), .skip_first = true};
      request.frame_count =
          link::ReceiveWholeMessage(socket, kMaxFramesKept, &request.frames, &wire);
      binding.Consumed(wire);  // the intake may read this peer's next message
      request.source_fd = wire.source_fd;
    } catch (const zmq::error_t& error) {
      if (error.num() == ETERM) return;
      continue;  // EINTR (a signal): the partial request is lost, its peer times out
    }
    request.received_us = kapfix::v1::NowMicros();
    try {
      Handle(socket, request);
    } catch (const zmq::error_t& error) {
      if (error.num() == ETERM) return;
    }
  }
}

void CommandServer::Impl::Handle(zmq::socket_t& socket, const Request& request) {
  // frames[0] is the routing id.
  std::vector<std::string_view> kept;
  for (std::size_t i = 1; i < request.frames.size(); ++i) kept.push_back(View(request.frames[i]));
  const RequestFrames frames = ParseRequestFrames(kept, request.frame_count - 1);
  Envelope envelope;
  envelope.delimiter = frames.delimiter;
  envelope.topic = frames.topic;
  envelope.payload = frames.payload;
  if (!frames.error.empty()) {
    Reply reply;
    reply.set_error(kapfix::v1::ERROR_CODE_MALFORMED);
    reply.set_reason(frames.error);
    SendReply(socket, request, envelope, std::move(reply), 0);
    return;
  }
  if (envelope.topic == kHeartbeatTopic) {
    HandleHeartbeat(socket, request, envelope);
  } else {
    HandleCommand(socket, request, envelope);
  }
}

// The station a command is counted against: one a peer cannot multiply by reconnecting.
std::string CommandServer::Impl::RateKey(const Request& request) const {
  // CurveZMQ: the station's key (named by the authorised-keys file).
  if (options.curve) return "key " + StationOf(request.frames.back());
  // Plain (loopback only, or --insecure): the peer's IP address, which a new connection keeps.
  // A local process can still bind other 127.x addresses: the shared bucket bounds that.
  const std::string address = binding.PeerAddressOf(request.source_fd);
  if (!address.empty()) return "address " + address.substr(0, address.rfind(':'));
  // No intake (ipc://, inproc://): the connection, which is all there is.
  return "connection " + std::string(View(request.frames[0]));
}

// Refuses the command when its station, or all stations together, are over their rate: before
// anything else is done with it, and without a lock the control loop takes. Behind the intake
// the station's connection is then not read until its next token, so what it sends meanwhile
// costs nothing here.
bool CommandServer::Impl::RateLimited(zmq::socket_t& socket, const Request& request,
                                      const Envelope& envelope) {
  if (!rate_limit) return false;
  const CommandRateLimit::Decision decision =
      rate_limit->Take(RateKey(request), CommandRateLimit::Clock::now());
  if (decision.allowed) return false;
  commands_rate_limited.fetch_add(1);
  binding.Hold(request.source_fd, decision.retry_at);
  Reply reply;
  reply.set_error(kapfix::v1::ERROR_CODE_RATE_LIMITED);
  reply.set_reason(decision.reason);
  SendReply(socket, request, envelope, std::move(reply), CommandSequenceOf(envelope.payload));
  return true;
}

void CommandServer::Impl::HandleCommand(zmq::socket_t& socket, const Request& request,
                                        const Envelope& envelope) {
  if (RateLimited(socket, request, envelope)) return;
  // The routing id identifies the station: sequence numbers are checked per connection.
  CommandIntake::Outcome outcome = intake.Answer(
      View(request.frames[0]), envelope.topic, envelope.payload, StationOf(request.frames.back()));
  if (outcome.station_heard) last_station_heard_us.store(request.received_us);
  SendReply(socket, request, envelope, std::move(outcome.reply), outcome.command_sequence);
}

void CommandServer::Impl::HandleHeartbeat(zmq::socket_t& socket, const Request& request,
                                          const Envelope& envelope) {
  kapfix::v1::Heartbeat heartbeat;
  // A heartbeat is not a command: nothing to refuse with a reply; a bad one is only counted.
  if (!kapfix::link::DecodeEnvelope(kHeartbeatTopic, envelope.payload, &heartbeat,
                                    kapfix::v1::kMaxCommandBytes, nullptr) ||
      !heartbeat_guard.Accept(View(request.frames[0]), heartbeat.header().sequence(), nullptr)) {
    heartbeats_ignored.fetch_add(1);
    return;
  }
  last_station_heard_us.store(request.received_us);
  // What this station lost of the streams (issue 15): kept per station, a notice when it grows.
  const std::string notice =
      subscriber_losses.Report(StationName(request), heartbeat, std::chrono::steady_clock::now());
  if (!notice.empty()) spdlog::warn("{}", notice);
  kapfix::v1::Heartbeat echo;
  kapfix::v1::Stamp(echo.mutable_header(), options.agent_id, ++heartbeat_sequence, options.boot_id);
  echo.set_echoed_send_time_us(heartbeat.header().send_time_us());
  echo.set_echoed_sequence(heartbeat.header().sequence());
  echo.set_echo_hold_us(echo.header().send_time_us() - request.received_us);
  echo.set_interval_ms(0);         // an answer, not a periodic heartbeat (those travel on the PUB)
  heartbeats_echoed.fetch_add(1);  // before sending, so a station that got it sees it counted
  Send(socket, request, envelope.delimiter, kHeartbeatTopic, echo.SerializeAsString());
}

std::string CommandServer::Impl::StationName(const Request& request) const {
  std::string name = StationOf(request.frames.back());  // its key's name, with CurveZMQ
  if (!name.empty()) return name;
  const std::string address =
      binding.PeerAddressOf(zmq_msg_get(request.frames.back().handle(), ZMQ_SRCFD));
  if (!address.empty()) return "at " + address;
  name = "with routing id ";  // a plain station without an intake: one per connection
  for (const unsigned char byte : View(request.frames[0])) {
    std::array<char, 3> hex{};
    std::snprintf(hex.data(), hex.size(), "%02x", byte);
    name += hex.data();
  }
  return name;
}

void CommandServer::Impl::SendReply(zmq::socket_t& socket, const Request& request,
                                    const Envelope& envelope, Reply reply,
                                    std::uint64_t command_sequence) {
  if (reply.ok()) {
    reply.set_error(kapfix::v1::ERROR_CODE_UNSPECIFIED);
    reply.clear_reason();
  } else if (reply.error() == kapfix::v1::ERROR_CODE_UNSPECIFIED) {
    // A refusal without a code would read as success to a careless station.
    reply.set_error(kapfix::v1::ERROR_CODE_INTERNAL);
    if (reply.reason().empty()) reply.set_reason("the agent refused without giving a reason");
  }
  reply.set_command_sequence(command_sequence);
  reply.clear_header();
  kapfix::v1::Stamp(reply.mutable_header(), options.agent_id, ++reply_sequence, options.boot_id);
  (reply.ok() ? commands_ok : commands_refused).fetch_add(1);
  const std::optional<std::string_view> topic =
      envelope.topic ? std::optional<std::string_view>(kReplyTopic) : std::nullopt;
  Send(socket, request, envelope.delimiter, topic, reply.SerializeAsString());
}

void CommandServer::Impl::Send(zmq::socket_t& socket, const Request& request, bool delimiter,
                               std::optional<std::string_view> topic, const std::string& payload) {
  // ROUTER never blocks on send: to a peer that is gone or full the message is dropped,
  // which is all that can be done for a station that stopped listening.
  constexpr auto kMore = zmq::send_flags::sndmore | zmq::send_flags::dontwait;
  (void)socket.send(zmq::buffer(View(request.frames[0])), kMore);
  if (delimiter) (void)socket.send(zmq::message_t(), kMore);
  if (topic) (void)socket.send(zmq::buffer(*topic), kMore);
  (void)socket.send(zmq::buffer(payload), zmq::send_flags::dontwait);
}

CommandServer::CommandServer(AgentControl& control, CommandServerOptions options)
    : impl_(std::make_unique<Impl>(control, std::move(options))) {}

CommandServer::~CommandServer() { Stop(); }

std::string CommandServer::Start() {
  if (impl_->thread.joinable()) throw std::runtime_error("command server already started");
  std::string why;
  if (impl_->options.rate_limit && !impl_->options.rate_limit->IsValid(&why)) {
    throw std::runtime_error("command server: rate limit: " + why);
  }
  return StartSocketThread(impl_.get(), "command server");
}

void CommandServer::Stop() {
  StopSocketThread(impl_.get());
  impl_->binding.Close();
}

std::vector<StationLosses> CommandServer::SubscriberLosses() const {
  return impl_->subscriber_losses.Stations();
}

CommandServer::Counters CommandServer::counters() const {
  Counters counters;
  counters.commands_ok = impl_->commands_ok.load();
  counters.commands_refused = impl_->commands_refused.load();
  counters.commands_rate_limited = impl_->commands_rate_limited.load();
  counters.heartbeats_echoed = impl_->heartbeats_echoed.load();
  counters.heartbeats_ignored = impl_->heartbeats_ignored.load();
  counters.last_station_heard_us = impl_->last_station_heard_us.load();
  if (impl_->zap) counters.keys_refused = impl_->zap->counters().refused;
  // Made before Start() returns (the bound promise orders it), never replaced while running.
  if (impl_->monitor) {
    const ConnectionMonitor::Counters connections = impl_->monitor->counters();
    counters.handshakes_failed = connections.handshakes_failed;
    counters.over_budget = connections.over_budget;
  }
  const link::BoundedIntake::Counters intake = impl_->binding.counters();
  counters.over_budget += intake.over_connections;
  counters.intake_paused = intake.paused;
  counters.intake_closed = intake.closed_over_budget;
  return counters;
}

}  // namespace kapfix::agent
