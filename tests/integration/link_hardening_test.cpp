// Issue 15: what a hostile or broken peer could still do to the real agent, each on loopback
// against kapfix-agent --sim, each failing before the hardening.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <unistd.h>
#include <zmq.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "kapfix/v1/envelope_codec.hpp"
#include "tests/integration/agent_process.hpp"
#include "tests/integration/child_process.hpp"
#include "tests/link/link_test_support.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;

// [kB] the resident set of a process, from /proc.
long ResidentKb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kb = 0;
      status >> kb;
      return kb;
    }
  }
  return -1;
}

// A blocking TCP connection to 127.0.0.1:port; -1 on failure.
int ConnectTcp(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// A request_state command addressed to any agent, stamped now.
kapfix::v1::Command StateRequest(std::uint64_t sequence) {
  kapfix::v1::Command command;
  command.mutable_request_state();
  kapfix::v1::Stamp(command.mutable_header(), "", sequence);
  return command;
}

// The reply to `bytes` (a command numbered `sequence`): replies to earlier requests, e.g. ones
// queued while the agent was starting, are skipped.
std::optional<kapfix::v1::Reply> ReplyTo(RawStation& station, const std::string& bytes,
                                         std::uint64_t sequence) {
  station.SendCommandBytes(bytes);
  while (const auto frames = station.ReceiveFrames()) {
    kapfix::v1::Reply reply;
    if (frames->size() == 3 && reply.ParseFromString((*frames)[2]) &&
        reply.command_sequence() == sequence) {
      return reply;
    }
  }
  return std::nullopt;
}

std::optional<kapfix::v1::Reply> ReplyTo(RawStation& station, const kapfix::v1::Command& command) {
  return ReplyTo(station, command.SerializeAsString(), command.header().sequence());
}

// The agent answers: retried while it starts (each try a new sequence number and send time).
std::optional<kapfix::v1::Reply> FirstReply(RawStation& station, std::uint64_t* sequence) {
  for (int attempt = 0; attempt < 10; ++attempt) {
    ++*sequence;
    if (auto reply = ReplyTo(station, StateRequest(*sequence))) {
      if (reply->ok()) return reply;
    }
  }
  return std::nullopt;
}

// Sets the soft limit on open files of this process; returns the previous one.
rlim_t SetOpenFileLimit(rlim_t soft) {
  rlimit limit{};
  getrlimit(RLIMIT_NOFILE, &limit);
  const rlim_t previous = limit.rlim_cur;
  limit.rlim_cur = std::min(soft, limit.rlim_max);
  setrlimit(RLIMIT_NOFILE, &limit);
  return previous;
}

// Item 1: one 64 MiB subscription took the agent to 6.8 GB. It is now refused by the
// publisher's maximum message size before anything is allocated for it, and the peer dropped.
TEST(LinkHardeningTest, SubscriptionOf64MiBLeavesTheAgentsMemoryWithin16MB) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  const long before_kb = ResidentKb(agent.pid());

  // Raw ZMTP 3.0, as a hostile peer would send it (a libzmq XSUB would itself build the
  // 64 MiB trie it sends): greeting, READY as a SUB, then one subscription message.
  const int fd = ConnectTcp(agent.stream_port());
  ASSERT_GE(fd, 0);
  std::string greeting(64, '\0');
  greeting[0] = static_cast<char>(0xFF);
  greeting[9] = 0x7F;
  greeting[10] = 3;  // version 3.0
  greeting.replace(12, 4, "NULL");
  const std::string ready = std::string("\x04\x19\x05READY\x0bSocket-Type\0\0\0\x03SUB", 27);
  const std::uint64_t size = (std::uint64_t{64} << 20U) + 1;
  std::string header = "\x02";  // a long, last frame
  for (int shift = 56; shift >= 0; shift -= 8) header += static_cast<char>((size >> shift) & 0xFFU);
  std::string subscription(size, 'a');
  subscription[0] = 1;  // 1 = subscribe, then the prefix
  const std::string wire = greeting + ready + header + subscription;
  std::size_t sent = 0;
  while (sent < wire.size()) {
    const ssize_t n = ::send(fd, wire.data() + sent, wire.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;  // the agent hung up: what it should do
    sent += static_cast<std::size_t>(n);
  }
  // Read until the agent closes the connection (bounded by the receive timeout).
  timeval timeout{30, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  char buffer[4096];
  ssize_t got = 0;
  while ((got = ::recv(fd, buffer, sizeof buffer, 0)) > 0) {
  }
  const bool closed = got == 0 || errno == ECONNRESET;
  ::close(fd);
  EXPECT_TRUE(closed) << "the agent kept the connection of a 64 MiB subscription";

  // The agent still answers, and its memory did not grow with the subscription.
  ++sequence;
  ASSERT_TRUE(ReplyTo(station, StateRequest(sequence))) << agent.log();
  const long after_kb = ResidentKb(agent.pid());
  std::printf("agent RSS %ld kB before, %ld kB after a 64 MiB subscription\n", before_kb, after_kb);
  EXPECT_LT(after_kb - before_kb, 16 * 1024);
}

// A plain (NULL mechanism) ZMTP 3.0 peer of type `socket_type` on a raw TCP connection, as a
// hostile peer would write it: a libzmq socket would itself hold every frame it sends.
class RawZmtpPeer {
 public:
  RawZmtpPeer(int port, const std::string& socket_type) : fd_(ConnectTcp(port)) {
    std::string greeting(64, '\0');
    greeting[0] = static_cast<char>(0xFF);
    greeting[9] = 0x7F;
    greeting[10] = 3;  // version 3.0
    greeting.replace(12, 4, "NULL");
    std::string body = std::string("\x05READY\x0bSocket-Type", 18);
    for (int shift = 24; shift >= 0; shift -= 8) {
      body += static_cast<char>((socket_type.size() >> shift) & 0xFFU);
    }
    body += socket_type;
    const std::string ready = std::string("\x04", 1) + static_cast<char>(body.size()) + body;
    ok_ = fd_ >= 0 && Write(greeting + ready);
    if (ok_) ok_ = Read(64).size() == 64 && ReadFrame().has_value();  // its greeting and READY
  }
  ~RawZmtpPeer() { Close(); }
  RawZmtpPeer(const RawZmtpPeer&) = delete;
  RawZmtpPeer& operator=(const RawZmtpPeer&) = delete;

  bool ok() const { return ok_; }
  enum class Sent { kAll, kStalled, kClosed };
  // One frame, as SendFrame, but it gives up once the agent's side has taken nothing for
  // `stall` (the kernel's buffers to it are full: it stopped reading this peer).
  Sent SendFrameUnlessStalled(const std::string& body, bool more, std::chrono::milliseconds stall) {
    std::string bytes(1, static_cast<char>(more ? 0x03 : 0x02));
    for (int shift = 56; shift >= 0; shift -= 8) {
      bytes += static_cast<char>((std::uint64_t{body.size()} >> shift) & 0xFFU);
    }
    bytes += body;
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      pollfd writable{fd_, POLLOUT, 0};
      if (::poll(&writable, 1, static_cast<int>(stall.count())) == 0) return Sent::kStalled;
      const ssize_t n =
          ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) continue;
      if (n <= 0) return Sent::kClosed;
      sent += static_cast<std::size_t>(n);
    }
    return Sent::kAll;
  }
  // True once the agent's side closed the connection (what it sent meanwhile is skipped);
  // false when it stayed open `limit` (a hang guard).
  bool WaitUntilClosed(std::chrono::seconds limit) {
    timeval timeout{static_cast<time_t>(limit.count()), 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    char buffer[4096];
    ssize_t got = 0;
    while ((got = ::recv(fd_, buffer, sizeof buffer, 0)) > 0) {
    }
    return got == 0 || errno == ECONNRESET;
  }
  void Close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  // One frame (a long one, 8-byte size) of `body`; false when the agent hung up.
  bool SendFrame(const std::string& body, bool more) {
    std::string header(1, static_cast<char>(more ? 0x03 : 0x02));
    for (int shift = 56; shift >= 0; shift -= 8) {
      header += static_cast<char>((std::uint64_t{body.size()} >> shift) & 0xFFU);
    }
    return Write(header) && Write(body);
  }
  // The frames of the next message (commands skipped); std::nullopt when the connection
  // closed or nothing came within 60 s.
  std::optional<std::vector<std::string>> ReceiveMessage() {
    std::vector<std::string> frames;
    while (const auto frame = ReadFrame()) {
      if (frame->command) continue;
      frames.push_back(frame->body);
      if (!frame->more) return frames;
    }
    return std::nullopt;
  }

 private:
  struct Frame {
    bool command = false;
    bool more = false;
    std::string body;
  };
  bool Write(const std::string& bytes) {
    std::size_t sent = 0;
    while (sent < bytes.size()) {
      const ssize_t n = ::send(fd_, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) return false;
      sent += static_cast<std::size_t>(n);
    }
    return true;
  }
  std::string Read(std::size_t count) {
    timeval timeout{60, 0};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    std::string bytes(count, '\0');
    std::size_t got = 0;
    while (got < count) {
      const ssize_t n = ::recv(fd_, bytes.data() + got, count - got, 0);
      if (n <= 0) return bytes.substr(0, got);
      got += static_cast<std::size_t>(n);
    }
    return bytes;
  }
  std::optional<Frame> ReadFrame() {
    const std::string flags = Read(1);
    if (flags.size() != 1) return std::nullopt;
    const auto bits = static_cast<unsigned char>(flags[0]);
    const std::string size_bytes = Read((bits & 0x02U) != 0 ? 8 : 1);
    std::uint64_t size = 0;
    for (const char byte : size_bytes) size = (size << 8U) | static_cast<unsigned char>(byte);
    Frame frame{.command = (bits & 0x04U) != 0, .more = (bits & 0x01U) != 0, .body = Read(size)};
    if (frame.body.size() != size) return std::nullopt;
    return frame;
  }

  int fd_ = -1;
  bool ok_ = false;
};

constexpr int kHugeFrames = 2000;
constexpr std::size_t kHugeFrameBytes =
    std::size_t{200} * 1000;  // under the command socket's 256 KiB

// Item 4: an unfinished multipart message (2,000 frames of 200 KB, never ended) pinned 600 MB.
// libzmq assembles a whole message before the agent sees any frame, so the agent's intake
// stops reading a peer that has sent more than its budget (1 MiB) the agent has not received
// as whole messages: the rest waits in the kernel's socket buffers, and the peer is closed
// once it has stayed there 10 s.
TEST(LinkHardeningTest, UnfinishedMultipartIsHeldWithin16MBWhileThePeerStaysConnected) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  const long before_kb = ResidentKb(agent.pid());

  RawZmtpPeer peer(agent.command_port(), "DEALER");
  ASSERT_TRUE(peer.ok());
  const std::string body(kHugeFrameBytes, 'x');
  int frames = 0;
  RawZmtpPeer::Sent sent = RawZmtpPeer::Sent::kAll;
  while (frames < kHugeFrames && sent == RawZmtpPeer::Sent::kAll) {
    // A stall of 2 s: the intake stopped reading (on a loaded machine it may come early,
    // which only makes the test send less).
    sent = peer.SendFrameUnlessStalled(body, /*more=*/true, std::chrono::seconds(2));
    if (sent == RawZmtpPeer::Sent::kAll) ++frames;
  }
  const long held_kb = ResidentKb(agent.pid());
  std::printf(
      "agent RSS %ld kB before, %ld kB with %d of %d frames of %zu B of an unfinished "
      "message sent when the agent stopped reading\n",
      before_kb, held_kb, frames, kHugeFrames, kHugeFrameBytes);
  EXPECT_EQ(sent, RawZmtpPeer::Sent::kStalled) << "the agent took the whole message or hung up";
  EXPECT_LT(frames, kHugeFrames);
  EXPECT_LT(held_kb - before_kb, 16 * 1024);
  // A station is answered meanwhile.
  ++sequence;
  EXPECT_TRUE(ReplyTo(station, StateRequest(sequence))) << agent.log();
  // And the peer that stays at its budget is closed.
  EXPECT_TRUE(peer.WaitUntilClosed(std::chrono::seconds(120)));
  ++sequence;
  EXPECT_TRUE(ReplyTo(station, StateRequest(sequence))) << agent.log();
}

// Item 4: a whole message of 2,000 frames took the agent to 497 MB (of 200 KB each; those no
// longer arrive whole, see above). It is refused as malformed, only its first frames kept.
TEST(LinkHardeningTest, MultipartOf2000FramesIsRefusedNamingTheFrameCount) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();

  RawZmtpPeer peer(agent.command_port(), "DEALER");
  ASSERT_TRUE(peer.ok());
  const std::string body(200, 'x');  // 2,000 x 200 B: within the intake's budget
  for (int i = 0; i < kHugeFrames; ++i) {
    ASSERT_TRUE(peer.SendFrame(body, /*more=*/i + 1 < kHugeFrames)) << i;
  }
  const auto answer = peer.ReceiveMessage();
  ASSERT_TRUE(answer.has_value()) << agent.log();
  ASSERT_EQ(answer->size(), 1U);
  kapfix::v1::Reply reply;
  ASSERT_TRUE(reply.ParseFromString(answer->front()));
  EXPECT_EQ(reply.error(), kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_THAT(reply.reason(), HasSubstr("got 2000 frames"));
}

// Item 1, by number: each subscription is at most 1 KiB, but a peer could send any number of
// distinct ones, each a branch of the trie libzmq keeps for its connection. The agent admits
// at most 32 per peer and ends the connection of one that sends more.
TEST(LinkHardeningTest, ManySubscriptionsFromOnePeerLeaveTheAgentsMemoryWithin16MB) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  const long before_kb = ResidentKb(agent.pid());

  RawZmtpPeer peer(agent.stream_port(), "SUB");
  ASSERT_TRUE(peer.ok());
  constexpr int kSubscriptions = 20'000;
  const std::string padding(56, 'p');
  int sent = 0;
  while (sent < kSubscriptions &&
         peer.SendFrame("\x01" + std::to_string(100000 + sent) + padding, /*more=*/false)) {
    ++sent;
  }
  EXPECT_TRUE(peer.WaitUntilClosed(std::chrono::seconds(120)))
      << "the agent kept a peer with " << sent << " subscriptions";
  const long after_kb = ResidentKb(agent.pid());
  std::printf(
      "agent RSS %ld kB before, %ld kB after %d of %d subscriptions of 62 bytes from one "
      "peer\n",
      before_kb, after_kb, sent, kSubscriptions);
  EXPECT_LT(after_kb - before_kb, 16 * 1024);
  // The refusal is logged around the time the connection ends, not necessarily before:
  // wait for the line (the bound only ends a test that would otherwise hang).
  const auto logged = [&agent] {
    return agent.log().find("more than 32 subscriptions from one peer") != std::string::npos;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!logged() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_THAT(agent.log(), HasSubstr("more than 32 subscriptions from one peer"));
  ++sequence;
  EXPECT_TRUE(ReplyTo(station, StateRequest(sequence))) << agent.log();
}

// Item 2: libzmq reads 'A;B' as "bind B from source A": the agent listened on 0.0.0.0.
TEST(LinkHardeningTest, SourceAndBindPairCommandAddressIsRefused) {
  TempDir temp;
  UnusedPort open_port;
  UnusedPort stream;
  const ProcessOutcome run = RunProcess(
      std::string(KAPFIX_AGENT) + " --sim --frames 1 --command-address " +
          "'tcp://127.0.0.1:0;0.0.0.0:" + std::to_string(open_port.port()) + "'" +
          " --stream-address tcp://127.0.0.1:" + std::to_string(stream.port()) + " --photos " +
          (temp.path() / "photos").string() + " --state-dir " + (temp.path() / "state").string(),
      temp.path() / "agent.err");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.err, HasSubstr("';' is not allowed"));
}

TEST(LinkHardeningTest, SourceAndBindPairInTheConfigurationIsRefused) {
  TempDir temp;
  UnusedPort open_port;
  UnusedPort stream;
  std::ofstream(temp.path() / "agent.json")
      << R"({"link": {"command": "tcp://127.0.0.1:0;0.0.0.0:)" << open_port.port() << R"("}})";
  const ProcessOutcome run = RunProcess(
      std::string(KAPFIX_AGENT) + " --sim --frames 1 --config " +
          (temp.path() / "agent.json").string() + " --stream-address " +
          "tcp://127.0.0.1:" + std::to_string(stream.port()) + " --photos " +
          (temp.path() / "photos").string() + " --state-dir " + (temp.path() / "state").string(),
      temp.path() / "agent.err");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_THAT(run.err, HasSubstr("';'"));
}

// Item 2: "tcp://localhost:P" passed the loopback check but libzmq could not bind it.
TEST(LinkHardeningTest, LocalhostCommandAddressIsBoundOnLoopback) {
  TempDir temp;
  UnusedPort command;
  UnusedPort stream;
  const int command_port = command.port();
  command.Release();
  stream.Release();
  ChildProcess agent(
      {KAPFIX_AGENT, "--sim", "--mode", "idle", "--command-address",
       "tcp://localhost:" + std::to_string(command_port), "--stream-address",
       "tcp://127.0.0.1:" + std::to_string(stream.port()), "--photos",
       (temp.path() / "photos").string(), "--state-dir", (temp.path() / "state").string()},
      temp.path() / "agent.out", temp.path() / "agent.err");
  RawStation station("tcp://127.0.0.1:" + std::to_string(command_port));
  std::uint64_t sequence = 0;
  EXPECT_TRUE(FirstReply(station, &sequence)) << ReadFile(temp.path() / "agent.err");
}

// Item 3: the agent ran out of file descriptors (soft limit 1,024, a silent connection held
// 30 s) and refused every station. It raises its limit and closes silent connections.
TEST(LinkHardeningTest, AuthorisedStationIsAnsweredBehind1100SilentConnections) {
  const rlim_t previous = SetOpenFileLimit(1024);  // what the agent inherits, as under systemd
  AgentProcess agent({"--mode", "idle"});
  SetOpenFileLimit(previous);
  {
    RawStation first(agent.command_endpoint());
    std::uint64_t sequence = 0;
    ASSERT_TRUE(FirstReply(first, &sequence)) << agent.log();
  }
  constexpr int kSilent = 1100;
  std::vector<int> silent;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(agent.command_port()));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  for (int i = 0; i < kSilent; ++i) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
    ASSERT_GE(fd, 0) << "the test's own descriptors ran out at " << i;
    (void)::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address);
    silent.push_back(fd);
  }
  RawStation station(agent.command_endpoint());
  const auto asked = std::chrono::steady_clock::now();
  const auto reply = ReplyTo(station, StateRequest(1));
  const double waited_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - asked).count();
  for (const int fd : silent) ::close(fd);
  ASSERT_TRUE(reply.has_value()) << agent.log();
  EXPECT_TRUE(reply->ok()) << reply->reason();
  std::printf("reply behind %d silent connections after %.0f ms (target: under 1 s)\n", kSilent,
              waited_ms);
}

// Item 8: captured command bytes were accepted again on a new connection.
TEST(LinkHardeningTest, ReplayedCommandOnANewConnectionIsRefused) {
  AgentProcess agent({"--mode", "idle"});
  std::uint64_t sequence = 0;
  std::string captured;
  {
    RawStation station(agent.command_endpoint());
    ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
    captured = StateRequest(++sequence).SerializeAsString();
    const auto first = ReplyTo(station, captured, sequence);
    ASSERT_TRUE(first && first->ok()) << (first ? first->reason() : "no reply");
  }
  RawStation attacker(agent.command_endpoint());
  const auto replayed = ReplyTo(attacker, captured, sequence);
  ASSERT_TRUE(replayed.has_value());
  EXPECT_FALSE(replayed->ok());
  EXPECT_EQ(replayed->error(), kapfix::v1::ERROR_CODE_STALE_SEQUENCE);
  EXPECT_THAT(replayed->reason(), HasSubstr("replayed"));
}

TEST(LinkHardeningTest, CommandStamped1970IsRefusedNamingTheSkew) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  kapfix::v1::Command old = StateRequest(++sequence);
  old.mutable_header()->set_send_time_us(1);
  const auto reply = ReplyTo(station, old);
  ASSERT_TRUE(reply.has_value());
  EXPECT_FALSE(reply->ok());
  EXPECT_THAT(reply->reason(), HasSubstr("behind the agent's clock"));
}

// Item 11: libprotobuf printed every invalid UTF-8 string to the agent's stderr, unthrottled.
TEST(LinkHardeningTest, InvalidUtf8IsRefusedAsMalformedWithoutALogLine) {
  AgentProcess agent({"--mode", "idle"});
  RawStation station(agent.command_endpoint());
  std::uint64_t sequence = 0;
  ASSERT_TRUE(FirstReply(station, &sequence)) << agent.log();
  kapfix::v1::Command command;
  command.mutable_take_photo()->set_note("PLACEHOLDER");
  kapfix::v1::Stamp(command.mutable_header(), "", ++sequence);
  std::string bytes = command.SerializeAsString();
  bytes.replace(bytes.find("PLACEHOLDER"), 11, "\xff\xfe bad!! \xc0\xaf");  // same length: 11
  for (int i = 0; i < 20; ++i) {
    const auto reply = ReplyTo(station, bytes, 0);  // unreadable: the reply names sequence 0
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_MALFORMED) << reply->reason();
  }
  ++sequence;
  ASSERT_TRUE(ReplyTo(station, StateRequest(sequence)));  // the agent is still there
  EXPECT_THAT(agent.log(), ::testing::Not(HasSubstr("UTF-8")));
}

}  // namespace
}  // namespace kapfix::testing
