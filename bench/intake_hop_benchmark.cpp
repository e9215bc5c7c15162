// kapfix-bench-intake-hop: what the bounded intake (issue 15, link/bounded_intake) adds to a
// station's round trip. A ROUTER echo server is reached over loopback TCP twice in the same
// run, once directly and once through a BoundedIntake in front of its unix socket (the peer
// measured in the same run), by a DEALER that sends one message and waits for its echo, one
// at a time; prints p50/p99 of both and their ratio, for small (command-sized) and large
// (200 KB) messages.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "link/bounded_intake.hpp"
#include "link/whole_message_receive.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Latency {
  double p50_us = 0;
  double p99_us = 0;
};

// Echoes every message on `socket` until the context ends, telling `intake` (if any) what it
// consumed, as the agent's servers do.
void Echo(zmq::socket_t& socket, kapfix::link::BoundedIntake* intake) {
  try {
    while (true) {
      std::vector<zmq::message_t> frames;
      kapfix::link::ReceivedWire wire{.skip_first = true};
      (void)kapfix::link::ReceiveWholeMessage(socket, 2, &frames, &wire);
      if (intake != nullptr) intake->Consumed(wire.source_fd, wire.bytes);
      socket.send(frames[0], zmq::send_flags::sndmore);
      socket.send(frames[1], zmq::send_flags::none);
    }
  } catch (const zmq::error_t&) {
    // ETERM: the benchmark is over.
  }
}

Latency RoundTrips(const std::string& endpoint, std::size_t bytes, int count) {
  zmq::context_t context(1);
  zmq::socket_t dealer(context, zmq::socket_type::dealer);
  dealer.set(zmq::sockopt::linger, 0);
  dealer.connect(endpoint);
  const std::string payload(bytes, 'x');
  std::vector<double> us;
  for (int i = 0; i < count + count / 10; ++i) {  // the first tenth warms up, not counted
    const auto start = Clock::now();
    dealer.send(zmq::buffer(payload), zmq::send_flags::none);
    zmq::message_t echo;
    (void)dealer.recv(echo);
    if (i >= count / 10) {
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - start).count());
    }
  }
  std::sort(us.begin(), us.end());
  return {us[us.size() / 2], us[us.size() * 99 / 100]};
}

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-bench-intake-hop: round trip directly and through the bounded intake"};
  int count = 5000;
  app.add_option("--count", count, "round trips per measurement")->check(CLI::Range(100, 1000000));
  CLI11_PARSE(app, argc, argv);

  zmq::context_t context(1);
  zmq::socket_t direct(context, zmq::socket_type::router);
  direct.set(zmq::sockopt::linger, 0);
  direct.bind("tcp://127.0.0.1:*");
  const std::string direct_endpoint = direct.get(zmq::sockopt::last_endpoint);

  char pattern[] = "/tmp/kapfix-bench-intake-XXXXXX";
  const std::filesystem::path dir = ::mkdtemp(pattern);
  const std::string path = (dir / "socket").string();
  zmq::socket_t relayed(context, zmq::socket_type::router);
  relayed.set(zmq::sockopt::linger, 0);
  relayed.bind("ipc://" + path);
  kapfix::link::BoundedIntakeOptions options = kapfix::link::IntakeWithBudget(1U << 20U);
  options.public_endpoint = "tcp://127.0.0.1:0";
  options.private_path = path;
  kapfix::link::BoundedIntake intake(options);
  const std::string intake_endpoint = intake.Start();

  std::thread direct_echo([&] { Echo(direct, nullptr); });
  std::thread relayed_echo([&] { Echo(relayed, &intake); });
  for (const std::size_t bytes : {std::size_t{100}, std::size_t{200'000}}) {
    const int n = bytes > 10'000 ? std::max(100, count / 10) : count;
    // Alternated, so that both see the same load on the machine.
    const Latency a1 = RoundTrips(direct_endpoint, bytes, n / 2);
    const Latency b1 = RoundTrips(intake_endpoint, bytes, n / 2);
    const Latency a2 = RoundTrips(direct_endpoint, bytes, n / 2);
    const Latency b2 = RoundTrips(intake_endpoint, bytes, n / 2);
    const Latency a{(a1.p50_us + a2.p50_us) / 2, (a1.p99_us + a2.p99_us) / 2};
    const Latency b{(b1.p50_us + b2.p50_us) / 2, (b1.p99_us + b2.p99_us) / 2};
    std::printf(
        "%zu B messages, %d round trips each: direct p50 %.1f us p99 %.1f us; through the intake "
        "p50 %.1f us p99 %.1f us; ratio intake/direct p50 %.2f p99 %.2f\n",
        bytes, n, a.p50_us, a.p99_us, b.p50_us, b.p99_us, b.p50_us / a.p50_us, b.p99_us / a.p99_us);
  }
  intake.Stop();
  context.shutdown();
  direct_echo.join();
  relayed_echo.join();
  std::filesystem::remove_all(dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kapfix-bench-intake-hop: %s\n", e.what());
    return 1;
  }
}
