// kapfix-bench-command-flood: the control loop's latency while stations flood the command
// socket (issue 15: p99 under 5 ms with 10 stations). Runs the real kapfix-agent --sim twice
// for the same number of frames on loopback, once quiet and once with N stations each sending
// request_state as fast as the agent answers (the peer measured in the same run), and prints
// the loop latency p50/p99/max of both from the agent's own telemetry.csv, as ratios to the
// quiet run, and the commands answered (OK and rate-limited).
//
// By default each station has its own CurveZMQ key, as N real stations would (the agent's
// rate limit counts per key); --plain floods unencrypted from 127.0.0.1, where all stations
// share one address and so one bucket. --no-limit raises the agent's rates out of reach, to
// measure the command path itself under the flood.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>
#include <zmq_addon.hpp>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/curve_key_file.hpp"
#include "link/curve_key_pair.hpp"

namespace {

using kapfix::link::CurveKeyPair;

struct Run {
  double p50_ms = 0;
  double p99_ms = 0;
  double max_ms = 0;
  double fps = 0;
  std::uint64_t ok = 0;
  std::uint64_t rate_limited = 0;
  std::uint64_t other = 0;
};

struct Counts {
  std::atomic<std::uint64_t> ok{0};
  std::atomic<std::uint64_t> rate_limited{0};
  std::atomic<std::uint64_t> other{0};
};

// The CurveZMQ keys of one flight: the agent's and one per station.
struct FlightKeys {
  CurveKeyPair agent;
  std::vector<CurveKeyPair> stations;
};

// One station: request_state, wait for the reply (at most 1 s), again, until `stop`.
void Station(const std::string& endpoint, const std::optional<CurveKeyPair>& own,
             const std::string& agent_public_key, const std::atomic<bool>& stop, Counts& counts) {
  zmq::context_t context(1);
  zmq::socket_t socket(context, zmq::socket_type::dealer);
  socket.set(zmq::sockopt::linger, 0);
  socket.set(zmq::sockopt::rcvtimeo, 1000);
  if (own) {
    socket.set(zmq::sockopt::curve_serverkey, agent_public_key);
    socket.set(zmq::sockopt::curve_publickey, own->public_key);
    socket.set(zmq::sockopt::curve_secretkey, own->secret_key);
  }
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
    if (!zmq::recv_multipart(socket, std::back_inserter(reply)) || reply.empty()) continue;
    kapfix::v1::Reply decoded;
    if (!decoded.ParseFromArray(reply.back().data(), static_cast<int>(reply.back().size()))) {
      counts.other.fetch_add(1);
    } else if (decoded.ok()) {
      counts.ok.fetch_add(1);
    } else if (decoded.error() == kapfix::v1::ERROR_CODE_RATE_LIMITED) {
      counts.rate_limited.fetch_add(1);
    } else if (counts.other.fetch_add(1) == 0) {
      std::fprintf(stderr, "first other reply: %s\n", decoded.reason().c_str());
    }
  }
}

// The agent's configuration file for a flight: CurveZMQ files when `keys`, the rates.
std::filesystem::path WriteConfig(const std::filesystem::path& dir,
                                  const std::optional<FlightKeys>& keys, bool no_limit) {
  nlohmann::json link = nlohmann::json::object();
  if (keys) {
    std::string error;
    if (!kapfix::link::WriteSecretKeyFile(dir / "agent.key", keys->agent, "agent", true, &error)) {
      throw std::runtime_error(error);
    }
    std::ofstream authorised(dir / "authorized_keys");
    for (std::size_t i = 0; i < keys->stations.size(); ++i) {
      authorised << keys->stations[i].public_key << " station" << i << "\n";
    }
    link["curve_secret_key_file"] = (dir / "agent.key").string();
    link["curve_authorized_keys_file"] = (dir / "authorized_keys").string();
  }
  if (no_limit) {
    link["command_rate_per_s"] = 100'000.0;
    link["command_burst"] = 100'000.0;
    link["all_commands_rate_per_s"] = 100'000.0;
  }
  std::filesystem::path path = dir / "config.json";
  std::ofstream(path) << nlohmann::json{{"link", link}}.dump(2);
  return path;
}

// p50, p99 and max of the loop_latency_ms column of the agent's telemetry.csv.
void ReadLatencies(const std::filesystem::path& csv, Run* run) {
  std::ifstream in(csv);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("no " + csv.string());
  std::size_t column = 0;
  {
    std::istringstream header(line);
    std::string name;
    while (std::getline(header, name, ',') && name != "loop_latency_ms") ++column;
  }
  std::vector<double> latencies;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t i = 0; i <= column && std::getline(row, cell, ','); ++i) {
    }
    if (!cell.empty()) latencies.push_back(std::stod(cell));
  }
  if (latencies.empty()) throw std::runtime_error("no latencies in " + csv.string());
  std::sort(latencies.begin(), latencies.end());
  const auto at = [&](double share) {
    return latencies[std::min(
        latencies.size() - 1,
        static_cast<std::size_t>(share * static_cast<double>(latencies.size())))];
  };
  run->p50_ms = at(0.50);
  run->p99_ms = at(0.99);
  run->max_ms = latencies.back();
}

Run Fly(const std::string& agent, int frames, int stations, int port,
        const std::filesystem::path& dir, const std::optional<FlightKeys>& keys, bool no_limit) {
  const std::string command = "tcp://127.0.0.1:" + std::to_string(port);
  std::vector<std::string> args = {agent,
                                   "--sim",
                                   "--config",
                                   WriteConfig(dir, keys, no_limit).string(),
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
  Counts counts;
  std::vector<std::thread> threads;
  for (int i = 0; i < stations; ++i) {
    std::optional<CurveKeyPair> own;
    if (keys) own = keys->stations[static_cast<std::size_t>(i)];
    threads.emplace_back(
        [&, own] { Station(command, own, keys ? keys->agent.public_key : "", stop, counts); });
  }
  int status = 0;
  waitpid(pid, &status, 0);
  stop = true;
  for (auto& thread : threads) thread.join();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("the agent failed; see " + (dir / "agent.err").string());
  }
  const nlohmann::json summary =
      nlohmann::json::parse(std::ifstream(dir / "report" / "summary.json"));
  Run run;
  ReadLatencies(dir / "report" / "telemetry.csv", &run);
  run.fps = summary["fps"];
  run.ok = counts.ok.load();
  run.rate_limited = counts.rate_limited.load();
  run.other = counts.other.load();
  return run;
}

void Print(const char* name, const Run& run, const Run& quiet, int frames) {
  const double seconds = run.fps > 0 ? frames / run.fps : 0;
  std::printf(
      "%s: loop p50 %.2f ms, p99 %.2f ms (x%.2f), max %.2f ms (x%.2f), %.1f fps; replies: %llu OK "
      "(%.0f/s), %llu rate-limited, %llu other\n",
      name, run.p50_ms, run.p99_ms, run.p99_ms / quiet.p99_ms, run.max_ms,
      run.max_ms / quiet.max_ms, run.fps, static_cast<unsigned long long>(run.ok),
      seconds > 0 ? static_cast<double>(run.ok) / seconds : 0.0,
      static_cast<unsigned long long>(run.rate_limited),
      static_cast<unsigned long long>(run.other));
}

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-bench-command-flood: loop latency under a command flood"};
  std::string agent = KAPFIX_AGENT;
  int frames = 600;
  int stations = 10;
  int port = 47555;
  bool plain = false;
  bool no_limit = false;
  app.add_option("--agent", agent, "kapfix-agent binary");
  app.add_option("--frames", frames, "frames per flight (30 fps: 600 = 20 s)");
  app.add_option("--stations", stations, "stations flooding commands")->check(CLI::Range(1, 1000));
  app.add_option("--port", port, "command port (the stream port is the next one)");
  app.add_flag("--plain", plain, "no CurveZMQ: every station floods from 127.0.0.1 unencrypted");
  app.add_flag("--no-limit", no_limit, "the agent's command rates out of reach");
  CLI11_PARSE(app, argc, argv);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("kapfix-flood-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir / "quiet");
  std::filesystem::create_directories(dir / "flood");
  std::optional<FlightKeys> keys;
  if (!plain) {
    keys.emplace();
    keys->agent = kapfix::link::GenerateCurveKeyPair();
    for (int i = 0; i < stations; ++i)
      keys->stations.push_back(kapfix::link::GenerateCurveKeyPair());
  }
  const Run quiet = Fly(agent, frames, 0, port, dir / "quiet", keys, no_limit);
  const Run flood = Fly(agent, frames, stations, port + 2, dir / "flood", keys, no_limit);
  std::printf("frames per flight: %d; stations flooding: %d (%s); agent's rate limit: %s\n", frames,
              stations, plain ? "plain, one address" : "CurveZMQ, a key each",
              no_limit ? "out of reach" : "default");
  Print("quiet", quiet, quiet, frames);
  Print("flood", flood, quiet, frames);
  std::printf("flood p99 %.2f ms (target: under 5 ms)\n", flood.p99_ms);
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
