#include "link/bounded_intake.hpp"

#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <zmq.hpp>

#include "link/whole_message_receive.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::link {
namespace {

// A ROUTER on a unix socket with an intake in front of it, on 127.0.0.1.
class IntakeWithRouter {
 public:
  explicit IntakeWithRouter(std::uint64_t budget_bytes) {
    router_.set(zmq::sockopt::linger, 0);
    router_.set(zmq::sockopt::rcvtimeo, 10'000);  // a hang guard only
    const std::string path = (temp_.path() / "socket").string();
    router_.bind("ipc://" + path);
    BoundedIntakeOptions options = IntakeWithBudget(budget_bytes);
    options.public_endpoint = "tcp://127.0.0.1:0";
    options.private_path = path;
    intake_ = std::make_unique<BoundedIntake>(options);
    const std::string endpoint = intake_->Start();
    port_ = std::atoi(endpoint.substr(endpoint.rfind(':') + 1).c_str());
  }
  int port() const { return port_; }
  zmq::socket_t& router() { return router_; }
  BoundedIntake& intake() { return *intake_; }

 private:
  kapfix::testing::TempDir temp_;
  zmq::context_t context_{1};
  zmq::socket_t router_{context_, zmq::socket_type::router};
  std::unique_ptr<BoundedIntake> intake_;
  int port_ = 0;
};

TEST(BoundedIntakeTest, AStationIsRelayedBothWaysAndNamedByItsAddress) {
  IntakeWithRouter server(1 << 20);
  zmq::context_t context(1);
  zmq::socket_t dealer(context, zmq::socket_type::dealer);
  dealer.set(zmq::sockopt::linger, 0);
  dealer.set(zmq::sockopt::rcvtimeo, 10'000);
  dealer.connect("tcp://127.0.0.1:" + std::to_string(server.port()));
  ASSERT_TRUE(dealer.send(zmq::str_buffer("hello"), zmq::send_flags::none));
  std::vector<zmq::message_t> frames;
  ReceivedWire wire{.skip_first = true};
  ASSERT_EQ(ReceiveWholeMessage(server.router(), 2, &frames, &wire), 2U);
  EXPECT_EQ(frames[1].to_string(), "hello");
  EXPECT_EQ(wire.bytes, ZmtpWireBytes(5, false));
  EXPECT_EQ(server.intake().PeerAddressOf(wire.source_fd).rfind("127.0.0.1:", 0), 0U);
  server.router().send(frames[0], zmq::send_flags::sndmore);
  server.router().send(zmq::str_buffer("world"), zmq::send_flags::none);
  zmq::message_t answer;
  ASSERT_TRUE(dealer.recv(answer));
  EXPECT_EQ(answer.to_string(), "world");
}

// [bytes] sends frames of 200 KB with the MORE flag (a multipart message never ended) until
// nothing more is taken for `stall`; how many bytes were taken.
std::uint64_t SendUntilStalled(int fd, std::chrono::milliseconds stall) {
  std::string frame = "\x03";
  constexpr std::uint64_t kBody = 200'000;
  for (int shift = 56; shift >= 0; shift -= 8) frame += static_cast<char>((kBody >> shift) & 0xFFU);
  frame += std::string(kBody, 'x');
  std::uint64_t sent = 0;
  while (sent < (std::uint64_t{1} << 30U)) {
    pollfd writable{fd, POLLOUT, 0};
    if (::poll(&writable, 1, static_cast<int>(stall.count())) == 0) return sent;
    const std::size_t at = sent % frame.size();
    const ssize_t n = ::send(fd, frame.data() + at, frame.size() - at, MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0 && errno != EAGAIN) return sent;
    if (n > 0) sent += static_cast<std::uint64_t>(n);
  }
  return sent;
}

TEST(BoundedIntakeTest, APeerIsNoLongerReadOnceItsBudgetIsUnconsumed) {
  constexpr std::uint64_t kBudget = 256 * 1024;
  IntakeWithRouter server(kBudget);
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(server.port()));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  // A ZMTP greeting and READY, then frames of a message that never ends.
  std::string greeting(64, '\0');
  greeting[0] = static_cast<char>(0xFF);
  greeting[9] = 0x7F;
  greeting[10] = 3;
  greeting.replace(12, 4, "NULL");
  const std::string ready = std::string(
      "\x04\x1c\x05READY\x0bSocket-Type\0\0\0\x06"
      "DEALER",
      30);
  const std::string start = greeting + ready;
  ASSERT_EQ(::send(fd, start.data(), start.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(start.size()));
  // The server's greeting and READY first, as a ZeroMQ peer waits for them.
  char answer[256];
  std::size_t got = 0;
  while (got < 64 + 2) {
    const ssize_t n = ::recv(fd, answer, sizeof answer, 0);
    ASSERT_GT(n, 0);
    got += static_cast<std::size_t>(n);
  }
  const std::uint64_t sent = SendUntilStalled(fd, std::chrono::seconds(2));
  const BoundedIntake::Counters counters = server.intake().counters();
  EXPECT_GE(counters.paused, 1U);
  // What the intake took: its budget, and what the kernel buffers on the way hold.
  std::printf("sent %llu bytes before the intake stopped reading (budget %llu)\n",
              static_cast<unsigned long long>(sent), static_cast<unsigned long long>(kBudget));
  EXPECT_LT(sent, std::uint64_t{1} << 30U);
  ::close(fd);
}

}  // namespace
}  // namespace kapfix::link
