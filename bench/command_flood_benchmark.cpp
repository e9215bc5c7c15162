// kapfix-bench-command-flood: the control loop's latency while stations flood the command
// socket (issue 15: p99 under 5 ms with 10 stations). Runs the real kapfix-agent --sim twice
// for the same number of frames on loopback, once quiet and once with N stations each sending
// request_state as fast as the agent answers (the peer measured in the same run), and prints
// the loop latency p50/p99 of both from the agent's own report, and the commands answered.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"

namespace {

struct Run {
  double p50_ms = 0;
  double p99_ms = 0;
  double fps = 0;
  std::uint64_t answered = 0;
};

// One station: request_state, wait for the reply (at most 1 s), again, until `stop`.
void Station(const std::string& endpoint, const std::atomic<bool>& stop,
             std::atomic<std::uint64_t>& answered) {
  zmq::context_t context(1);
  zmq::socket_t socket(context, zmq::socket_type::dealer);
  socket.set(zmq::sockopt::linger, 0);
  socket.set(zmq::sockopt::rcvtimeo, 1000);
  socket.connect(endpoint);
  std::uint64_t sequence = 0;
  while (!stop) {
    kapfix::v1::Command command;
    command.mutable_request_state();
    kapfix::v1::Stamp(command.mutable_header(), "", ++sequence);
    const std::string bytes = command.SerializeAsString();
    socket.send(zmq::message_t(), zmq::send_flags::sndmore);
    socket.send(zmq::buffer(std::string_view("command")), zmq::send_flags::sndmore);
    socket.send(zmq::buffer(bytes), zmq::send_flags::none);
    std::vector<zmq::message_t> reply;
    if (zmq::recv_multipart(socket, std::back_inserter(reply))) answered.fetch_add(1);
  }
}

Run Fly(const std::string& agent, int frames, int stations, int port,
        const std::filesystem::path& dir) {
  const std::string command = "tcp://127.0.0.1:" + std::to_string(port);
  std::vector<std::string> args = {agent,
                                   "--sim",
                                   "--frames",
                                   std::to_string(frames),
                                   "--report",
                                   (dir / "report").string(),
                                   "--command-address",
                                   command,
                                   "--stream-address",
                                   "tcp://127.0.0.1:" + std::to_string(port + 1),
                                   "--photos",
                                   (dir / "photos").string(),
                                   "--state-dir",
                                   (dir / "state").string()};
  std::vector<char*> argv;
  for (auto& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, (dir / "agent.out").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, (dir / "agent.err").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  if (posix_spawn(&pid, agent.c_str(), &actions, nullptr, argv.data(), environ) != 0) {
    throw std::runtime_error("cannot start " + agent);
  }
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> answered{0};
  std::vector<std::thread> threads;
  for (int i = 0; i < stations; ++i) {
    threads.emplace_back([&] { Station(command, stop, answered); });
  }
  int status = 0;
  waitpid(pid, &status, 0);
  stop = true;
  for (auto& thread : threads) thread.join();
  const nlohmann::json summary =
      nlohmann::json::parse(std::ifstream(dir / "report" / "summary.json"));
  return {summary["loop_latency_p50_ms"], summary["loop_latency_p99_ms"], summary["fps"],
          answered.load()};
}

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-bench-command-flood: loop latency under a command flood"};
  std::string agent = KAPFIX_AGENT;
  int frames = 600;
  int stations = 10;
  int port = 47555;
  app.add_option("--agent", agent, "kapfix-agent binary");
  app.add_option("--frames", frames, "frames per flight (30 fps: 600 = 20 s)");
  app.add_option("--stations", stations, "stations flooding commands");
  app.add_option("--port", port, "command port (the stream port is the next one)");
  CLI11_PARSE(app, argc, argv);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kapfix-flood-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir / "quiet");
  std::filesystem::create_directories(dir / "flood");
  const Run quiet = Fly(agent, frames, 0, port, dir / "quiet");
  const Run flood = Fly(agent, frames, stations, port + 2, dir / "flood");
  std::printf("frames per flight: %d; stations flooding: %d\n", frames, stations);
  std::printf("quiet: loop p50 %.2f ms, p99 %.2f ms, %.1f fps\n", quiet.p50_ms, quiet.p99_ms,
              quiet.fps);
  std::printf("flood: loop p50 %.2f ms, p99 %.2f ms, %.1f fps, %llu commands answered\n",
              flood.p50_ms, flood.p99_ms, flood.fps,
              static_cast<unsigned long long>(flood.answered));
  std::printf("p99 ratio flood/quiet: %.2f (target: flood p99 under 5 ms)\n",
              flood.p99_ms / quiet.p99_ms);
  std::filesystem::remove_all(dir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kapfix-bench-command-flood: %s\n", e.what());
    return 1;
  }
}
