// kapfix-agent: the platform's program (SPEC §4). Reads one configuration file plus flags;
// with no hardware configured it flies in simulation and says so. Wiring only: the flags are
// AgentCommandLine's, the flight is Agent's, the summary is the flight report's.
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "agent/agent.hpp"
#include "agent/agent_command_line.hpp"
#include "agent/pipeline/flight_report.hpp"
#include "agent/preflight/preflight.hpp"

namespace {

using namespace kapfix::agent;

volatile std::sig_atomic_t g_stop_requested = 0;

extern "C" void OnSignal(int /*signal*/) { g_stop_requested = 1; }

int Fail(const std::string& message, int code) {
  std::fprintf(stderr, "kapfix-agent: %s\n", message.c_str());
  return code;
}

// One PASS/FAIL line per check; 0 when all pass.
int RunPreflightChecks(const AgentConfig& config, const PreflightOptions& checks) {
  bool all_pass = true;
  for (const PreflightCheck& check : RunPreflight(config, checks)) {
    std::printf("%s\n", check.Line().c_str());
    all_pass = all_pass && check.pass;
  }
  return all_pass ? 0 : 1;
}

// Runs the flight until its frames are done or SIGINT/SIGTERM.
PipelineStats RunUntilStopped(Agent& agent) {
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  std::atomic<bool> done{false};
  std::thread stopper([&agent, &done] {
    while (!done) {
      if (g_stop_requested) {
        agent.Stop();
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  PipelineStats stats = agent.Run();
  done = true;
  stopper.join();
  return stats;
}

// The flight's summary on stdout and, with --report DIR, the flight report in DIR.
int Report(Agent& agent, const AgentConfig& config, const PipelineStats& stats,
           const std::string& report_dir) {
  const auto records = agent.telemetry().records();
  agent.photos().Flush();  // the photos fired before the end, written
  const FlightDescription flight{
      .controller = kapfix::v1::WordOf(config.gains.controller()),
      .shutter = kapfix::v1::WordOf(config.photo.shutter()),
      .simulated = agent.simulated(),
      .world = config.simulation.world.Describe(),
      .scene = config.simulation.scene,
      .motion = std::string(ToString(config.simulation.motion)),
  };
  const nlohmann::json summary =
      FlightSummary(ComputeFlightFigures(records, stats, agent.true_deg_per_px()),
                    ComputePhotoFigures(agent.photos().Saved()), stats, flight);
  std::cout << summary.dump(2) << std::endl;
  try {
    WriteFlightReport(report_dir, summary, records);
  } catch (const std::exception& e) {
    return Fail(e.what(), 1);
  }
  return stats.error.empty() ? 0 : Fail(stats.error, 1);
}

int Main(int argc, char** argv) {
  spdlog::set_default_logger(spdlog::stderr_color_mt("kapfix-agent"));
  CLI::App app{"kapfix-agent: keeps the camera locked on a view while the platform swings"};
  AgentCommandLine line(app);  // not const: parsing writes into it
  CLI11_PARSE(app, argc, argv);

  AgentConfig config;
  std::string error;
  if (!line.BuildConfig(&config, &error)) return Fail(error, 2);
  if (line.preflight()) return RunPreflightChecks(config, line.BuildPreflight());
  const AgentOptions options = line.BuildOptions(config);

  std::unique_ptr<Agent> agent;
  try {
    agent = std::make_unique<Agent>(config, options);
  } catch (const std::exception& e) {
    return Fail(e.what(), 1);
  }
  if (agent->simulated()) {
    spdlog::info("{}: running in simulation (scene {}, {} motion, world: {}){}",
                 line.force_sim() ? "--sim" : "no hardware configured", config.simulation.scene,
                 ToString(config.simulation.motion), config.simulation.world.Describe(),
                 options.frames > 0 ? ", " + std::to_string(options.frames) + " frames" : "");
  }
  spdlog::info("{}", agent->Describe());
  const PipelineStats stats = RunUntilStopped(*agent);

  if (!line.report_dir().empty()) return Report(*agent, config, stats, line.report_dir());
  spdlog::info(
      "processed {} frames in {:.1f} s ({} dropped, {} watchdog stalls, {} servo errors, {} "
      "servo driver outages, {} camera reconnects)",
      stats.processed, stats.wall_s, stats.dropped, stats.watchdog_stalls, stats.servo_errors,
      stats.servo_outages, stats.camera_reconnects);
  return stats.error.empty() ? 0 : Fail(stats.error, 1);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    return Fail(e.what(), 1);
  } catch (...) {
    return Fail("unexpected error", 1);
  }
}
