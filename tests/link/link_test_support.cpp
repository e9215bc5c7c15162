#include "tests/link/link_test_support.hpp"

#include <arpa/inet.h>
#include <google/protobuf/unknown_field_set.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <zmq_addon.hpp>

namespace kapfix::testing {

int PortOf(const std::string& endpoint) {
  return std::stoi(endpoint.substr(endpoint.rfind(':') + 1));
}

kapfix::agent::StreamPublisherOptions TestPublisherOptions() {
  kapfix::agent::StreamPublisherOptions options;
  options.bind_endpoint = "tcp://127.0.0.1:*";
  options.agent_id = kAgentId;
  options.heartbeat_interval = std::chrono::milliseconds(50);
  return options;
}

kapfix::agent::CommandServerOptions TestServerOptions() {
  kapfix::agent::CommandServerOptions options;
  options.bind_endpoint = "tcp://127.0.0.1:*";
  options.agent_id = kAgentId;
  return options;
}

FakeAgent::FakeAgent(kapfix::agent::StreamPublisherOptions publisher_options,
                     kapfix::agent::CommandServerOptions server_options)
    : publisher(std::move(publisher_options)), server(control, std::move(server_options)) {
  control.SetPublisher(&publisher);
  stream_endpoint = publisher.Start();
  command_endpoint = server.Start();
}

kapfix::v1::Command Stamped(kapfix::v1::Command command, std::uint64_t sequence) {
  kapfix::v1::Stamp(command.mutable_header(), kAgentId, sequence);
  return command;
}

RawStation::RawStation(const std::string& endpoint) : socket_(context_, zmq::socket_type::dealer) {
  socket_.set(zmq::sockopt::linger, 0);
  socket_.connect(endpoint);
}

void RawStation::SendFrames(const std::vector<std::string>& frames) {
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const bool last = i + 1 == frames.size();
    (void)socket_.send(zmq::buffer(frames[i]),
                       last ? zmq::send_flags::none : zmq::send_flags::sndmore);
  }
}

void RawStation::SendCommandBytes(const std::string& bytes) { SendFrames({"", "command", bytes}); }

std::optional<std::vector<std::string>> RawStation::ReceiveFrames(std::chrono::milliseconds wait) {
  std::array<zmq::pollitem_t, 1> items{{{socket_.handle(), 0, ZMQ_POLLIN, 0}}};
  if (zmq::poll(items, wait) == 0) return std::nullopt;
  std::vector<zmq::message_t> messages;
  if (!zmq::recv_multipart(socket_, std::back_inserter(messages))) return std::nullopt;
  std::vector<std::string> frames;
  for (const auto& message : messages) frames.push_back(message.to_string());
  return frames;
}

std::optional<kapfix::v1::Reply> RawStation::Exchange(const kapfix::v1::Command& command) {
  return ExchangeBytes(command.SerializeAsString());
}

std::optional<kapfix::v1::Reply> RawStation::ExchangeBytes(const std::string& bytes) {
  SendCommandBytes(bytes);
  const auto frames = ReceiveFrames();
  if (!frames || frames->size() != 3 || (*frames)[1] != "reply") return std::nullopt;
  kapfix::v1::Reply reply;
  if (!reply.ParseFromString((*frames)[2])) return std::nullopt;
  return reply;
}

RawSubscriber::RawSubscriber(const std::string& endpoint, const std::vector<std::string>& topics,
                             int receive_high_water_mark)
    : socket_(context_, zmq::socket_type::sub) {
  socket_.set(zmq::sockopt::linger, 0);
  socket_.set(zmq::sockopt::rcvhwm, receive_high_water_mark);
  socket_.set(zmq::sockopt::subscribe, "heartbeat");
  for (const auto& topic : topics) socket_.set(zmq::sockopt::subscribe, topic);
  socket_.connect(endpoint);
}

bool RawSubscriber::Ready() { return Next("heartbeat").has_value(); }

std::optional<std::string> RawSubscriber::Next(const std::string& topic,
                                               std::chrono::milliseconds wait) {
  const auto deadline = std::chrono::steady_clock::now() + wait;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return std::nullopt;
    std::array<zmq::pollitem_t, 1> items{{{socket_.handle(), 0, ZMQ_POLLIN, 0}}};
    if (zmq::poll(items, left) == 0) return std::nullopt;
    std::vector<zmq::message_t> messages;
    if (!zmq::recv_multipart(socket_, std::back_inserter(messages)) || messages.size() != 2) {
      continue;
    }
    if (messages[0].to_string_view() == topic) return messages[1].to_string();
  }
}

UnusedPort::UnusedPort() : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof address;
  if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    throw std::runtime_error("cannot reserve a port");
  }
  port_ = ntohs(address.sin_port);
}

UnusedPort::~UnusedPort() { Release(); }

void UnusedPort::Release() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

kapfix::v1::Telemetry LargeTelemetry(std::uint64_t frame) {
  kapfix::v1::Telemetry telemetry;
  telemetry.set_frame_number(frame);
  telemetry.GetReflection()
      ->MutableUnknownFields(&telemetry)
      ->AddLengthDelimited(1000, std::string(100'000, 'p'));
  return telemetry;
}

}  // namespace kapfix::testing
