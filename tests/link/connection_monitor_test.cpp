// ConnectionMonitor's connection budget (issue 15, item 3): a flood of silent connections
// must not keep a station out.
#include "link/connection_monitor.hpp"

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <string>
#include <thread>
#include <zmq.hpp>

#include "tests/link/link_test_support.hpp"

namespace kapfix::link {
namespace {

// A TCP connection to 127.0.0.1:port, closed with the object.
class TcpConnection {
 public:
  explicit TcpConnection(int port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
    timeval timeout{30, 0};  // a hang guard only
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  }
  ~TcpConnection() { ::close(fd_); }
  TcpConnection(const TcpConnection&) = delete;
  TcpConnection& operator=(const TcpConnection&) = delete;

  bool connected() const { return connected_; }
  // The start of a ZMTP 3.0 handshake: a whole greeting (NULL mechanism), as a station sends.
  void SendGreeting() {
    std::string greeting(64, '\0');
    greeting[0] = static_cast<char>(0xFF);
    greeting[9] = 0x7F;
    greeting[10] = 3;
    greeting.replace(12, 4, "NULL");
    (void)::send(fd_, greeting.data(), greeting.size(), MSG_NOSIGNAL);
  }
  // Reads (the agent's greeting) until the agent ends the connection: true, or the hang
  // guard passes: false.
  bool EndedByTheAgent() {
    char buffer[256];
    ssize_t got = 0;
    while ((got = ::recv(fd_, buffer, sizeof buffer, 0)) > 0) {
    }
    return got == 0 || errno == ECONNRESET;
  }

 private:
  int fd_;
  bool connected_ = false;
};

// Waits until `done()` or 30 s pass (a hang guard only); whether it became true.
template <typename Condition>
bool WaitUntil(Condition done) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!done()) {
    if (std::chrono::steady_clock::now() > give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// The budget full (a station that has begun its handshake, then a silent connection), a new
// connection used to be shut down itself, so a station could not get in until a silent one
// timed out. Now the silent one makes room; the station, older, is kept.
TEST(ConnectionMonitorTest, ConnectionOverTheBudgetShutsDownASilentOneNotAStation) {
  zmq::context_t context(1);
  zmq::socket_t socket(context, zmq::socket_type::router);
  socket.set(zmq::sockopt::linger, 0);
  socket.set(zmq::sockopt::handshake_ivl, 0);  // none times out by itself here
  ConnectionMonitor monitor("test server", ConnectionMonitorOptions{.max_connections = 2});
  monitor.Start(context, socket);
  // Before the monitor is joined, also when an assertion returns early: it stops on ETERM.
  struct ShutdownFirst {
    zmq::context_t& context;
    ~ShutdownFirst() { context.shutdown(); }
  } shutdown_first{context};
  socket.bind("tcp://127.0.0.1:*");
  const int port = kapfix::testing::PortOf(socket.get(zmq::sockopt::last_endpoint));

  TcpConnection station(port);
  ASSERT_TRUE(station.connected());
  station.SendGreeting();
  ASSERT_TRUE(WaitUntil([&] { return monitor.counters().accepted == 1; }));
  TcpConnection silent(port);
  ASSERT_TRUE(silent.connected());
  ASSERT_TRUE(WaitUntil([&] { return monitor.counters().accepted == 2; }));

  TcpConnection newcomer(port);
  ASSERT_TRUE(newcomer.connected());
  ASSERT_TRUE(WaitUntil([&] { return monitor.counters().over_budget == 1; }));
  EXPECT_TRUE(silent.EndedByTheAgent());
}

}  // namespace
}  // namespace kapfix::link
