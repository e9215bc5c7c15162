#include "tools/ctl/commands/link_flags.hpp"

#include <optional>
#include <string>

#include "link/curve_key_file.hpp"
#include "tools/ctl/commands/command_output.hpp"

namespace kapfix::ctl {

void AddLinkFlags(CLI::App& app, LinkArguments* link) {
  app.add_option("--agent", link->host, "agent host name or address")->capture_default_str();
  app.add_option("--command-port", link->command_port, "agent command port (ROUTER)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535));
  app.add_option("--stream-port", link->stream_port, "agent stream port (PUB)")
      ->capture_default_str()
      ->check(CLI::Range(1, 65535));
  app.add_option("--timeout", link->timeout_ms,
                 "[ms] wait this long for a reply, or for any message from the agent")
      ->capture_default_str()
      ->check(CLI::Range(1, 3'600'000));
  app.add_option("--agent-id", link->agent_id,
                 "address only the agent with this id (default: whichever listens)");
  auto* key_option =
      app.add_option("--key", link->key_file,
                     "this station's secret key file (kapfix-keygen NAME writes NAME.key)")
          ->check(CLI::ExistingFile);
  auto* agent_key_option =
      app.add_option("--agent-key", link->agent_key_file,
                     "the agent's public key file (its .pub): with --key, the link uses CurveZMQ")
          ->check(CLI::ExistingFile);
  key_option->needs(agent_key_option);
  agent_key_option->needs(key_option);
}

bool ReadCurveKeys(LinkArguments* link) {
  if (link->key_file.empty()) return true;
  std::string why;
  const auto station = kapfix::link::ReadSecretKeyFile(link->key_file, &why);
  const auto agent =
      station ? kapfix::link::ReadPublicKeyFile(link->agent_key_file, &why) : std::nullopt;
  if (!agent) {
    Error(why);
    return false;
  }
  link->curve = kapfix::link::CurveClientKeys{*station, *agent};
  return true;
}

}  // namespace kapfix::ctl
