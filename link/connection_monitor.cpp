#include "link/connection_monitor.hpp"

#include <linux/tcp.h>  // tcp_info with tcpi_bytes_received (glibc's <netinet/tcp.h> lacks it)
#include <netinet/in.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <zmq.h>

#include <cstddef>
#include <cstring>
#include <list>
#include <optional>
#include <unordered_map>
#include <utility>

namespace kapfix::link {
namespace {

constexpr int kEvents = ZMQ_EVENT_ACCEPTED | ZMQ_EVENT_DISCONNECTED | ZMQ_EVENT_CLOSED |
                        ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL | ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                        ZMQ_EVENT_HANDSHAKE_FAILED_AUTH;

// [bytes] a ZMTP greeting: a peer that has sent less cannot have begun a handshake, so it
// cannot be a station yet.
constexpr std::uint64_t kGreetingBytes = 64;

// [bytes] what the kernel has received on `fd` from its peer; std::nullopt when it is not a
// TCP connection (ipc) or no longer open.
std::optional<std::uint64_t> BytesReceived(int fd) {
  tcp_info info{};
  socklen_t size = sizeof info;
  if (::getsockopt(fd, IPPROTO_TCP, TCP_INFO, &info, &size) != 0 ||
      size < offsetof(tcp_info, tcpi_bytes_received) + sizeof info.tcpi_bytes_received) {
    return std::nullopt;
  }
  return info.tcpi_bytes_received;
}

}  // namespace

ConnectionMonitor::ConnectionMonitor(std::string what, ConnectionMonitorOptions options)
    : what_(std::move(what)), options_(options) {}

ConnectionMonitor::~ConnectionMonitor() {
  if (thread_.joinable()) thread_.join();
}

void ConnectionMonitor::Start(zmq::context_t& context, zmq::socket_t& socket) {
  const std::string endpoint = "inproc://kapfix-monitor-" + what_;
  if (zmq_socket_monitor(socket.handle(), endpoint.c_str(), kEvents) != 0) throw zmq::error_t();
  zmq::socket_t events(context, zmq::socket_type::pair);
  events.set(zmq::sockopt::linger, 0);
  // Wakes once a second to write a due summary when no event comes.
  events.set(zmq::sockopt::rcvtimeo, 1000);
  events.connect(endpoint);
  thread_ = std::thread([this, events = std::move(events)]() mutable { Serve(events); });
}

ConnectionMonitor::Counters ConnectionMonitor::counters() const {
  return {accepted_.load(), over_budget_.load(), handshakes_failed_.load()};
}

void ConnectionMonitor::Serve(zmq::socket_t& events) {
  using Clock = std::chrono::steady_clock;
  // Descriptors of the connections now open, oldest first, and where each is in that order.
  std::list<int> open_order;
  std::unordered_map<int, std::list<int>::iterator> open;
  const auto close_record = [&](int fd) {
    const auto found = open.find(fd);
    if (found == open.end()) return;
    open_order.erase(found->second);
    open.erase(found);
  };
  // The oldest open connection that has not sent a whole greeting; -1 if every one has.
  const auto silent_one = [&]() {
    for (const int fd : open_order) {
      const std::optional<std::uint64_t> received = BytesReceived(fd);
      if (received && *received < kGreetingBytes) return fd;
    }
    return -1;
  };
  std::uint64_t failed_unreported = 0;
  std::uint64_t over_budget_unreported = 0;
  Clock::time_point last_summary{};
  while (true) {
    zmq::message_t event;
    zmq::message_t address;
    try {
      if (events.recv(event)) {
        (void)events.recv(address);  // second frame: the endpoint
        std::uint16_t id = 0;
        std::uint32_t value = 0;  // the descriptor, for ACCEPTED and DISCONNECTED
        if (event.size() >= 6) {
          std::memcpy(&id, event.data(), sizeof id);
          std::memcpy(&value, static_cast<const char*>(event.data()) + 2, sizeof value);
        }
        const int fd = static_cast<int>(value);
        if (id == ZMQ_EVENT_ACCEPTED) {
          accepted_.fetch_add(1);
          close_record(fd);  // a number libzmq reused before its close event reached us
          bool admitted = open.size() < options_.max_connections;
          if (!admitted) {
            // Over the budget: a silent connection makes room, so that silent ones cannot keep
            // a station out; only when none is silent is the newcomer refused.
            const int silent = silent_one();
            admitted = silent >= 0;
            const int refused = admitted ? silent : fd;
            ::shutdown(refused, SHUT_RDWR);
            close_record(refused);
            over_budget_.fetch_add(1);
            ++over_budget_unreported;
          }
          if (admitted) open.emplace(fd, open_order.insert(open_order.end(), fd));
        } else if (id == ZMQ_EVENT_DISCONNECTED || id == ZMQ_EVENT_CLOSED) {
          close_record(fd);
        } else if (id == ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL ||
                   id == ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL ||
                   id == ZMQ_EVENT_HANDSHAKE_FAILED_AUTH) {
          handshakes_failed_.fetch_add(1);
          ++failed_unreported;
        }
      }
    } catch (const zmq::error_t& error) {
      if (error.num() == ETERM) return;
    }
    if ((failed_unreported > 0 || over_budget_unreported > 0) &&
        Clock::now() - last_summary >= options_.summary_period) {
      spdlog::warn(
          "{}: {} handshake(s) refused and {} connection(s) over the budget of {} in the "
          "last {} s; {} open",
          what_, failed_unreported, over_budget_unreported, options_.max_connections,
          std::chrono::duration_cast<std::chrono::seconds>(options_.summary_period).count(),
          open.size());
      failed_unreported = 0;
      over_budget_unreported = 0;
      last_summary = Clock::now();
    }
  }
}

}  // namespace kapfix::link
