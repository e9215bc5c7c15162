#include "link/bounded_intake.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstddef>
#include <cstring>
#include <list>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>

namespace kapfix::link {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kBufferBytes =
    std::size_t{256} * 1024;                  // [bytes] relayed per read, each direction
constexpr std::uint64_t kGreetingBytes = 64;  // [bytes] a ZMTP greeting
// [ms] how often a peer at its budget is looked at again while no report comes.
constexpr int kPausedPollMs = 100;

std::int64_t Nanoseconds(Clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
}

std::string ErrnoText(const char* what) { return std::string(what) + ": " + std::strerror(errno); }

// The unix address `fd`'s peer is bound to, as bytes (an abstract one starts with '\0');
// empty when it has none or `fd` is no unix connection.
std::string UnixPeerName(int fd) {
  sockaddr_un address{};
  socklen_t size = sizeof address;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&address), &size) != 0 ||
      address.sun_family != AF_UNIX || size <= offsetof(sockaddr_un, sun_path)) {
    return {};
  }
  return {address.sun_path, size - offsetof(sockaddr_un, sun_path)};
}

std::string AddressText(const sockaddr_storage& address) {
  char host[INET6_ADDRSTRLEN] = {};
  if (address.ss_family == AF_INET) {
    const auto& in = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &in.sin_addr, host, sizeof host);
    return std::string(host) + ":" + std::to_string(ntohs(in.sin_port));
  }
  if (address.ss_family == AF_INET6) {
    const auto& in6 = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &in6.sin6_addr, host, sizeof host);
    return "[" + std::string(host) + "]:" + std::to_string(ntohs(in6.sin6_port));
  }
  return "?";
}

// What the agent's thread and the intake's thread share about one peer.
struct PeerShared {
  std::atomic<std::uint64_t> consumed{0};  // [bytes] reported by the agent
  std::atomic<bool> paused{false};         // a report should wake the intake
  std::atomic<bool> disconnect{false};     // the agent asked for the peer to be closed
  // [ns of steady_clock] the agent asked for nothing to be read from the peer before this.
  std::atomic<std::int64_t> held_until_ns{0};
  std::string address;  // "HOST:PORT"
};

// [ms] until the peer's hold ends, rounded up; 0 when it is not held.
int HeldForMs(const PeerShared& shared, Clock::time_point now) {
  const std::int64_t left_ns = shared.held_until_ns.load() - Nanoseconds(now);
  return left_ns <= 0 ? 0 : static_cast<int>((left_ns + 999'999) / 1'000'000);
}

// Bytes read from one side, waiting to be written to the other.
struct Pending {
  std::vector<char> bytes = std::vector<char>(kBufferBytes);
  std::size_t begin = 0;
  std::size_t end = 0;
  bool empty() const { return begin == end; }
};

struct Peer;

// What an epoll event names: a peer's descriptor, either side.
struct PeerSide {
  Peer* peer;
  bool up;  // the intake's connection to the agent, else the peer's own
};

// epoll's event bits are poll's (Linux): the relay computes them once for both.
static_assert(EPOLLIN == POLLIN && EPOLLOUT == POLLOUT && EPOLLRDHUP == POLLRDHUP &&
              EPOLLHUP == POLLHUP && EPOLLERR == POLLERR);

struct Peer {
  int down = -1;     // the TCP connection from the peer
  int up = -1;       // the intake's connection to the agent
  std::string name;  // `up`'s abstract address, the key of the shared map
  std::shared_ptr<PeerShared> shared;
  Pending to_up;
  Pending to_down;
  bool down_eof = false;
  bool up_eof = false;
  bool closed = false;
  std::uint64_t forwarded = 0;      // [bytes] relayed to the agent
  std::uint64_t credit = 0;         // [bytes] of `forwarded` accounted for, at most all of it
  std::uint64_t consumed_seen = 0;  // [bytes] shared->consumed already credited
  Clock::time_point credited_at;
  bool paused = false;
  Clock::time_point paused_since;
  // epoll: the tags its descriptors are registered with, and what each waits for now.
  PeerSide down_tag{this, false};
  PeerSide up_tag{this, true};
  bool watched = false;
  std::uint32_t down_events = 0;
  std::uint32_t up_events = 0;
};

// Reads what `from` has into `into` (at most `limit` bytes); false on end of stream or error.
// `eof` set on end of stream.
bool ReadInto(int from, Pending& into, std::size_t limit, bool* eof, std::uint64_t* got) {
  const ssize_t n = ::recv(from, into.bytes.data(), std::min(limit, into.bytes.size()), 0);
  if (n > 0) {
    into.begin = 0;
    into.end = static_cast<std::size_t>(n);
    *got = static_cast<std::uint64_t>(n);
    return true;
  }
  *got = 0;
  if (n == 0) {
    *eof = true;
    return true;
  }
  return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
}

// Writes what it can of `from` to `to`; false on error.
bool WriteFrom(Pending& from, int to) {
  while (!from.empty()) {
    const ssize_t n = ::send(to, from.bytes.data() + from.begin, from.end - from.begin,
                             MSG_NOSIGNAL | MSG_DONTWAIT);
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    from.begin += static_cast<std::size_t>(n);
  }
  return true;
}

// A listening TCP socket on `endpoint` ("tcp://HOST:PORT"); throws.
int Listen(const std::string& endpoint) {
  constexpr std::string_view kScheme = "tcp://";
  if (endpoint.rfind(kScheme, 0) != 0) throw std::runtime_error("not a tcp endpoint: " + endpoint);
  const std::string rest = endpoint.substr(kScheme.size());
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos) throw std::runtime_error("no port in " + endpoint);
  std::string host = rest.substr(0, colon);
  std::string port = rest.substr(colon + 1);
  if (port == "*") port = "0";
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICHOST | AI_NUMERICSERV;
  hints.ai_family = host == "*" ? AF_INET : AF_UNSPEC;  // '*' is IPv4, as libzmq reads it
  addrinfo* found = nullptr;
  const int rc = ::getaddrinfo(host == "*" ? nullptr : host.c_str(), port.c_str(), &hints, &found);
  if (rc != 0 || found == nullptr) {
    throw std::runtime_error("cannot resolve " + endpoint + ": " + ::gai_strerror(rc));
  }
  const int fd = ::socket(found->ai_family, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  const int one = 1;
  if (fd < 0 || ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0 ||
      ::bind(fd, found->ai_addr, found->ai_addrlen) != 0 || ::listen(fd, SOMAXCONN) != 0) {
    const std::string why = ErrnoText(("cannot bind " + endpoint).c_str());
    ::freeaddrinfo(found);
    if (fd >= 0) ::close(fd);
    throw std::runtime_error(why);
  }
  ::freeaddrinfo(found);
  return fd;
}

}  // namespace

std::uint64_t ZmtpWireBytes(std::uint64_t frame_bytes, bool curve) {
  // CurveZMQ: "\x07MESSAGE", 8-byte nonce, 16-byte MAC, 1 flags byte, then the frame.
  const std::uint64_t body = frame_bytes + (curve ? 33 : 0);
  return body + (body <= 255 ? 2 : 9);
}

bool BoundedIntakeOptions::IsValid(std::string* error) const {
  const auto fail = [&](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (public_endpoint.rfind("tcp://", 0) != 0) return fail("the public endpoint must be tcp://");
  if (private_path.empty() || private_path.size() >= sizeof(sockaddr_un{}.sun_path)) {
    return fail("the private path must be 1 to 107 characters");
  }
  // The handshake (greeting, CurveZMQ HELLO and INITIATE: under 1 KiB) is never consumed.
  if (budget_bytes < 4096) return fail("budget_bytes must be at least 4 KiB");
  if (over_budget_limit.count() <= 0) return fail("over_budget_limit must be positive");
  if (max_connections == 0) return fail("max_connections must be at least 1");
  return true;
}

struct BoundedIntake::Impl {
  explicit Impl(BoundedIntakeOptions opts) : options(std::move(opts)) {}

  void Run();
  std::pair<std::uint32_t, std::uint32_t> Interest(const Peer& peer, Clock::time_point now) const;
  void Watch(Peer& peer, Clock::time_point now);
  int NextTimeoutMs(Clock::time_point now);
  void Sweep(Clock::time_point now);
  void Accept(Clock::time_point now);
  bool ConnectUp(Peer& peer);
  void Service(Peer& peer, short down_events, short up_events, Clock::time_point now);
  void Credit(Peer& peer, Clock::time_point now) const;
  std::uint64_t Room(const Peer& peer) const;
  void Close(Peer& peer);
  void LogClosed(Clock::time_point now, const std::string& address);

  const BoundedIntakeOptions options;
  int listener = -1;
  int wake = -1;             // eventfd: Stop() and reports for paused peers
  int epoll = -1;            // the wake, the listener and both descriptors of every peer
  bool listening = false;    // intake thread only: the listener is watched for EPOLLIN
  bool timed_peers = false;  // intake thread only: a peer is paused or held
  std::atomic<bool> stopping{false};
  std::thread thread;
  std::uint64_t next_name = 0;
  Clock::time_point accept_paused_until{};  // intake thread only
  Clock::time_point last_relay_failure_logged{};

  mutable std::mutex mutex;  // guards `shared`
  std::unordered_map<std::string, std::shared_ptr<PeerShared>> shared;

  std::list<Peer> peers;  // intake thread only; oldest first

  std::atomic<std::uint64_t> accepted{0};
  std::atomic<std::uint64_t> over_connections{0};
  std::atomic<std::uint64_t> paused_count{0};
  std::atomic<std::uint64_t> closed_over_budget{0};
  std::atomic<std::uint64_t> open{0};
  std::atomic<std::uint64_t> held{0};

  // Log summary (intake thread only).
  Clock::time_point last_logged{};
  std::uint64_t not_logged = 0;
};

void BoundedIntake::Impl::Credit(Peer& peer, Clock::time_point now) const {
  const std::uint64_t consumed = peer.shared->consumed.load();
  const auto elapsed_us =
      std::chrono::duration_cast<std::chrono::microseconds>(now - peer.credited_at).count();
  const std::uint64_t allowance =
      options.allowance_bytes_per_s *
      static_cast<std::uint64_t>(std::max<std::int64_t>(0, elapsed_us)) / 1'000'000;
  if (allowance > 0 && options.allowance_bytes_per_s > 0) {
    // Advanced by the time the whole bytes stand for, so no fraction is lost.
    peer.credited_at += std::chrono::microseconds(
        static_cast<std::int64_t>(allowance * 1'000'000 / options.allowance_bytes_per_s));
  }
  // Credit never runs ahead of what was relayed: reports and the allowance can only account
  // for bytes already sent, never bank room for a later message.
  peer.credit = std::min(peer.forwarded, peer.credit + (consumed - peer.consumed_seen) + allowance);
  peer.consumed_seen = consumed;
}

std::uint64_t BoundedIntake::Impl::Room(const Peer& peer) const {
  const std::uint64_t outstanding = peer.forwarded - peer.credit;
  return outstanding >= options.budget_bytes ? 0 : options.budget_bytes - outstanding;
}

void BoundedIntake::Impl::Close(Peer& peer) {
  if (peer.closed) return;
  peer.closed = true;
  if (peer.down >= 0) ::close(peer.down);
  if (peer.up >= 0) ::close(peer.up);
  peer.down = peer.up = -1;
  if (!peer.name.empty()) {
    const std::lock_guard lock(mutex);
    shared.erase(peer.name);
  }
}

void BoundedIntake::Impl::LogClosed(Clock::time_point now, const std::string& address) {
  if (now - last_logged < options.log_period) {
    ++not_logged;
    return;
  }
  spdlog::warn(
      "{}: closed {}: {} bytes sent without the agent receiving a whole message for {} ms{}",
      options.what, address, options.budget_bytes, options.over_budget_limit.count(),
      not_logged == 0
          ? std::string()
          : " (and " + std::to_string(not_logged) + " other peer(s) since the last line)");
  last_logged = now;
  not_logged = 0;
}

bool BoundedIntake::Impl::ConnectUp(Peer& peer) {
  peer.up = ::socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (peer.up < 0) return false;
  // A unique abstract address (no file): the agent's side reads it with getpeername().
  sockaddr_un own{};
  own.sun_family = AF_UNIX;
  const std::string name = std::string(1, '\0') + "kapfix-intake-" + std::to_string(::getpid()) +
                           "-" + std::to_string(reinterpret_cast<std::uintptr_t>(this)) + "-" +
                           std::to_string(++next_name);
  std::memcpy(own.sun_path, name.data(), name.size());
  const auto own_size = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name.size());
  sockaddr_un agent{};
  agent.sun_family = AF_UNIX;
  std::memcpy(agent.sun_path, options.private_path.data(), options.private_path.size());
  if (::bind(peer.up, reinterpret_cast<const sockaddr*>(&own), own_size) != 0 ||
      ::connect(peer.up, reinterpret_cast<const sockaddr*>(&agent), sizeof agent) != 0) {
    return false;  // EAGAIN: the agent's backlog is full; the peer is closed, it may retry
  }
  peer.name = name;
  const std::lock_guard lock(mutex);
  shared.emplace(peer.name, peer.shared);
  return true;
}

void BoundedIntake::Impl::Accept(Clock::time_point now) {
  std::size_t live = 0;
  for (const Peer& peer : peers) live += peer.closed ? 0 : 1;
  while (true) {
    sockaddr_storage from{};
    socklen_t size = sizeof from;
    const int fd = ::accept4(listener, reinterpret_cast<sockaddr*>(&from), &size,
                             SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      // Out of descriptors: the connection stays queued in the kernel, and the listener
      // readable; it is looked at again after a pause rather than in a busy loop.
      if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
        accept_paused_until = now + std::chrono::milliseconds(kPausedPollMs);
      }
      return;
    }
    accepted.fetch_add(1);
    // As libzmq does on its own TCP sockets: a relayed message is written in pieces, which
    // Nagle's algorithm would hold back for the peer's delayed acknowledgement.
    const int one = 1;
    (void)::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    if (live >= options.max_connections) {
      // A peer that has not sent a whole greeting cannot be a station yet: it makes room.
      const auto silent = std::find_if(peers.begin(), peers.end(), [](const Peer& peer) {
        return !peer.closed && peer.forwarded < kGreetingBytes;
      });
      over_connections.fetch_add(1);
      if (silent == peers.end()) {
        ::close(fd);
        continue;
      }
      Close(*silent);
      --live;
    }
    ++live;
    Peer& peer = peers.emplace_back();
    peer.down = fd;
    peer.shared = std::make_shared<PeerShared>();
    peer.shared->address = AddressText(from);
    peer.credited_at = now;
    if (!ConnectUp(peer)) {
      if (now - last_relay_failure_logged >= options.log_period) {  // at most a line a period
        spdlog::warn("{}: cannot relay {} to the agent: {}", options.what, peer.shared->address,
                     std::strerror(errno));
        last_relay_failure_logged = now;
      }
      Close(peer);
      --live;
      continue;
    }
    Watch(peer, now);
  }
}

void BoundedIntake::Impl::Service(Peer& peer, short down_events, short up_events,
                                  Clock::time_point now) {
  const auto fail = [&] { Close(peer); };
  // A peer that reset, or hung up while it waits at its budget, is gone: nothing it still
  // sends would be read. The agent's side gone while the peer is not reading: the same.
  if ((down_events & (POLLHUP | POLLERR)) != 0 || ((down_events & POLLRDHUP) != 0 && peer.paused) ||
      (up_events & POLLERR) != 0 || ((up_events & POLLHUP) != 0 && !peer.to_down.empty())) {
    return fail();
  }
  if (peer.shared->disconnect.load()) return fail();
  Credit(peer, now);
  // A paused peer is read again only once a quarter of its budget is free (a message was
  // consumed), not for every few bytes of allowance: its pause, and the limit on it, last.
  if (peer.paused && Room(peer) >= options.budget_bytes / 4) {
    peer.paused = false;
    peer.shared->paused.store(false);
  }
  // Peer -> agent, within the budget, unless the agent holds the peer.
  if ((down_events & (POLLIN | POLLHUP | POLLERR)) != 0 && peer.to_up.empty() && !peer.down_eof &&
      !peer.paused && HeldForMs(*peer.shared, now) == 0) {
    const std::uint64_t room = Room(peer);
    if (room > 0) {
      std::uint64_t got = 0;
      if (!ReadInto(peer.down, peer.to_up, static_cast<std::size_t>(room), &peer.down_eof, &got)) {
        return fail();
      }
      peer.forwarded += got;
    }
  }
  if (!WriteFrom(peer.to_up, peer.up)) return fail();
  // Agent -> peer: not bounded here (the agent decides what it sends).
  if ((up_events & (POLLIN | POLLHUP | POLLERR)) != 0 && peer.to_down.empty() && !peer.up_eof) {
    std::uint64_t got = 0;
    if (!ReadInto(peer.up, peer.to_down, kBufferBytes, &peer.up_eof, &got)) return fail();
  }
  if (!WriteFrom(peer.to_down, peer.down)) return fail();
  // Either side gone and what it sent passed on: the connection ends on both sides.
  if ((peer.down_eof && peer.to_up.empty()) || (peer.up_eof && peer.to_down.empty())) {
    return fail();
  }
  if (Room(peer) == 0 && !peer.paused) {
    peer.paused = true;
    peer.paused_since = now;
    peer.shared->paused.store(true);
    paused_count.fetch_add(1);
    Credit(peer, now);  // a report that came in between is seen at the next wake
  }
  if (peer.paused && now - peer.paused_since >= options.over_budget_limit) {
    closed_over_budget.fetch_add(1);
    LogClosed(now, peer.shared->address);
    fail();
  }
}

// What the intake waits for on each of the peer's descriptors now (poll(2) bits, which are
// epoll's too).
std::pair<std::uint32_t, std::uint32_t> BoundedIntake::Impl::Interest(const Peer& peer,
                                                                      Clock::time_point now) const {
  const bool reading = peer.to_up.empty() && !peer.down_eof && !peer.paused &&
                       HeldForMs(*peer.shared, now) == 0 && Room(peer) > 0;
  // POLLRDHUP only while paused: it stays set once the peer shut down, and is what tells that
  // a paused peer went.
  const std::uint32_t down = (peer.paused ? POLLRDHUP : 0U) | (reading ? POLLIN : 0U) |
                             (peer.to_down.empty() ? 0U : POLLOUT);
  const std::uint32_t up =
      (peer.to_down.empty() && !peer.up_eof ? POLLIN : 0U) | (peer.to_up.empty() ? 0U : POLLOUT);
  return {down, up};
}

// Registers the peer's descriptors with epoll, or changes what they wait for.
void BoundedIntake::Impl::Watch(Peer& peer, Clock::time_point now) {
  if (peer.closed) return;
  const auto [down, up] = Interest(peer, now);
  const auto watch = [&](int fd, std::uint32_t events, std::uint32_t& current, void* tag) {
    if (peer.watched && events == current) return;
    epoll_event event{};
    event.events = events;
    event.data.ptr = tag;
    (void)::epoll_ctl(epoll, peer.watched ? EPOLL_CTL_MOD : EPOLL_CTL_ADD, fd, &event);
    current = events;
  };
  watch(peer.down, down, peer.down_events, &peer.down_tag);
  watch(peer.up, up, peer.up_events, &peer.up_tag);
  peer.watched = true;
}

// [ms] how long the next wait may last (-1: until an event); watches the listener again once
// accepting may resume. Only a paused or held peer needs a timeout; looking for them is
// O(peers), and only while one of them is (a flood held at its rate, a peer at its budget).
int BoundedIntake::Impl::NextTimeoutMs(Clock::time_point now) {
  const bool accepting = now >= accept_paused_until;
  int timeout_ms = accepting ? -1 : kPausedPollMs;
  if (timed_peers) {
    for (const Peer& peer : peers) {
      const int wait_ms = peer.paused ? kPausedPollMs : HeldForMs(*peer.shared, now);
      if (wait_ms > 0 && (timeout_ms < 0 || wait_ms < timeout_ms)) timeout_ms = wait_ms;
    }
  }
  if (accepting != listening) {
    epoll_event event{};
    event.events = accepting ? EPOLLIN : 0U;
    event.data.ptr = &listener;
    (void)::epoll_ctl(epoll, EPOLL_CTL_MOD, listener, &event);
    listening = accepting;
  }
  return timeout_ms;
}

// After a round: forgets closed peers, clears ended holds (and watches those peers for
// reading again), and notes whether any peer is still paused or held.
void BoundedIntake::Impl::Sweep(Clock::time_point now) {
  timed_peers = false;
  for (auto it = peers.begin(); it != peers.end();) {
    if (it->closed) {
      it = peers.erase(it);
      continue;
    }
    std::int64_t until_ns = it->shared->held_until_ns.load();
    if (until_ns != 0 && until_ns <= Nanoseconds(now)) {
      (void)it->shared->held_until_ns.compare_exchange_strong(until_ns, 0);
      Watch(*it, now);
    }
    timed_peers = timed_peers || it->paused || it->shared->held_until_ns.load() != 0;
    it = std::next(it);
  }
  open.store(peers.size());
}

void BoundedIntake::Impl::Run() {
  constexpr int kMaxEvents = 256;
  std::array<epoll_event, kMaxEvents> events{};
  // Peers with something to do in this round, and their events (down, up).
  std::unordered_map<Peer*, std::pair<short, short>> ready;
  while (!stopping.load()) {
    const int n = ::epoll_wait(epoll, events.data(), kMaxEvents, NextTimeoutMs(Clock::now()));
    if (n < 0 && errno != EINTR) {
      spdlog::error("{}: epoll_wait failed: {}", options.what, std::strerror(errno));
      return;
    }
    const Clock::time_point now = Clock::now();
    bool woken = false;
    bool accept_ready = false;
    ready.clear();
    for (int i = 0; i < n; ++i) {
      const epoll_event& event = events[static_cast<std::size_t>(i)];
      if (event.data.ptr == &wake) {
        std::uint64_t count = 0;
        (void)!::read(wake, &count, sizeof count);
        woken = true;
      } else if (event.data.ptr == &listener) {
        accept_ready = (event.events & EPOLLIN) != 0;
      } else {
        const auto* side = static_cast<const PeerSide*>(event.data.ptr);
        auto& entry = ready[side->peer];
        (side->up ? entry.second : entry.first) |= static_cast<short>(event.events);
      }
    }
    // A wake (a report for a paused peer, a disconnect) or a timeout: every peer that may
    // have something to do without an event of its own.
    if (woken || timed_peers || n == 0) {
      for (Peer& peer : peers) {
        if (peer.paused || peer.shared->disconnect.load() ||
            peer.shared->held_until_ns.load() != 0) {
          ready.try_emplace(&peer, 0, 0);
        }
      }
    }
    for (auto& [peer, got] : ready) {
      if (peer->closed) continue;
      Service(*peer, got.first, got.second, now);
      Watch(*peer, now);
    }
    if (accept_ready) Accept(now);
    Sweep(now);
  }
}

BoundedIntake::BoundedIntake(BoundedIntakeOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}

BoundedIntake::~BoundedIntake() { Stop(); }

std::string BoundedIntake::Start() {
  if (impl_->thread.joinable()) throw std::runtime_error(impl_->options.what + " already started");
  std::string why;
  if (!impl_->options.IsValid(&why)) throw std::runtime_error(impl_->options.what + ": " + why);
  impl_->listener = Listen(impl_->options.public_endpoint);
  impl_->wake = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  impl_->epoll = ::epoll_create1(EPOLL_CLOEXEC);
  epoll_event wake_event{};
  wake_event.events = EPOLLIN;
  wake_event.data.ptr = &impl_->wake;
  epoll_event listen_event{};
  listen_event.events = EPOLLIN;
  listen_event.data.ptr = &impl_->listener;
  if (impl_->wake < 0 || impl_->epoll < 0 ||
      ::epoll_ctl(impl_->epoll, EPOLL_CTL_ADD, impl_->wake, &wake_event) != 0 ||
      ::epoll_ctl(impl_->epoll, EPOLL_CTL_ADD, impl_->listener, &listen_event) != 0) {
    const std::string failure = ErrnoText("eventfd or epoll");
    ::close(impl_->listener);
    if (impl_->wake >= 0) ::close(impl_->wake);
    if (impl_->epoll >= 0) ::close(impl_->epoll);
    impl_->listener = impl_->wake = impl_->epoll = -1;
    throw std::runtime_error(failure);
  }
  impl_->listening = true;
  sockaddr_storage bound{};
  socklen_t size = sizeof bound;
  ::getsockname(impl_->listener, reinterpret_cast<sockaddr*>(&bound), &size);
  impl_->stopping.store(false);
  impl_->thread = std::thread([impl = impl_.get()] { impl->Run(); });
  return "tcp://" + AddressText(bound);
}

void BoundedIntake::Stop() {
  if (!impl_->thread.joinable()) return;
  impl_->stopping.store(true);
  const std::uint64_t one = 1;
  (void)!::write(impl_->wake, &one, sizeof one);
  impl_->thread.join();
  for (Peer& peer : impl_->peers) impl_->Close(peer);
  impl_->peers.clear();
  impl_->open.store(0);
  ::close(impl_->listener);
  ::close(impl_->wake);
  ::close(impl_->epoll);
  impl_->listener = impl_->wake = impl_->epoll = -1;
}

void BoundedIntake::Consumed(int agent_fd, std::uint64_t wire_bytes) {
  const std::string name = UnixPeerName(agent_fd);
  if (name.empty()) return;
  std::shared_ptr<PeerShared> peer;
  {
    const std::lock_guard lock(impl_->mutex);
    const auto found = impl_->shared.find(name);
    if (found == impl_->shared.end()) return;
    peer = found->second;
  }
  peer->consumed.fetch_add(wire_bytes);
  if (peer->paused.load()) {
    const std::uint64_t one = 1;
    (void)!::write(impl_->wake, &one, sizeof one);
  }
}

void BoundedIntake::Disconnect(int agent_fd) {
  const std::string name = UnixPeerName(agent_fd);
  if (name.empty()) return;
  {
    const std::lock_guard lock(impl_->mutex);
    const auto found = impl_->shared.find(name);
    if (found == impl_->shared.end()) return;
    found->second->disconnect.store(true);
  }
  const std::uint64_t one = 1;
  (void)!::write(impl_->wake, &one, sizeof one);
}

void BoundedIntake::Hold(int agent_fd, std::chrono::steady_clock::time_point until) {
  const std::string name = UnixPeerName(agent_fd);
  if (name.empty()) return;
  const Clock::time_point latest = Clock::now() + kMaxHold;
  const std::int64_t until_ns = Nanoseconds(std::min(until, latest));
  const std::lock_guard lock(impl_->mutex);
  const auto found = impl_->shared.find(name);
  if (found == impl_->shared.end()) return;
  // Never shortens a hold: the latest end asked for stands.
  std::int64_t held = found->second->held_until_ns.load();
  while (held < until_ns && !found->second->held_until_ns.compare_exchange_weak(held, until_ns)) {
  }
  impl_->held.fetch_add(1);
  // No wake: the intake looks at the hold before it next reads the peer, and leaves the peer
  // out of its poll from then on.
}

std::string BoundedIntake::PeerAddressOf(int agent_fd) const {
  const std::string name = UnixPeerName(agent_fd);
  const std::lock_guard lock(impl_->mutex);
  const auto found = impl_->shared.find(name);
  return found == impl_->shared.end() ? std::string() : found->second->address;
}

BoundedIntake::Counters BoundedIntake::counters() const {
  return {impl_->accepted.load(),     impl_->over_connections.load(),
          impl_->paused_count.load(), impl_->closed_over_budget.load(),
          impl_->open.load(),         impl_->held.load()};
}

}  // namespace kapfix::link
