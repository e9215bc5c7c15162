// kapfix-keygen: makes a CurveZMQ key pair for an agent or a station (SPEC §5, issue 5).
// Writes NAME.key (secret, mode 0600) and NAME.pub (public, one line).
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <string>

#include "link/curve_key_file.hpp"
#include "link/curve_key_pair.hpp"

namespace {

constexpr const char* kUsage =
    "Then:\n"
    "  on the agent:   link.curve_secret_key_file = AGENT.key\n"
    "                  link.curve_authorized_keys_file = a file with one line per station\n"
    "                  (cat STATION.pub >> authorized_keys)\n"
    "  on a station:   kapfix-ctl --key STATION.key --agent-key AGENT.pub ...\n"
    "                  kapfix-station --key STATION.key --agent-key AGENT.pub\n"
    "Give out .pub files only; a .key file stays on its machine.\n";

int Main(int argc, char** argv) {
  CLI::App app{"kapfix-keygen: make a CurveZMQ key pair for a kapfix agent or station"};
  app.footer(kUsage);
  std::string name;
  std::filesystem::path folder = ".";
  bool force = false;
  app.add_option("NAME", name, "who the keys are for, e.g. agent or laptop; files NAME.key/.pub")
      ->required()
      ->check([](const std::string& text) {
        const bool plain = !text.empty() && text.find_first_of("/ \t\n") == std::string::npos;
        return plain ? std::string() : std::string("NAME must be a word without / or spaces");
      });
  app.add_option("--dir", folder, "folder to write them in")
      ->capture_default_str()
      ->check(CLI::ExistingDirectory);
  app.add_flag("--force", force, "replace existing files of that name");
  CLI11_PARSE(app, argc, argv);

  const kapfix::link::CurveKeyPair pair = kapfix::link::GenerateCurveKeyPair();
  const std::filesystem::path secret = folder / (name + ".key");
  const std::filesystem::path public_file = folder / (name + ".pub");
  std::string error;
  if (!kapfix::link::WriteSecretKeyFile(secret, pair, name, force, &error) ||
      !kapfix::link::WritePublicKeyFile(public_file, pair.public_key, name, force, &error)) {
    std::cerr << "kapfix-keygen: " << error << std::endl;
    return 1;
  }
  std::cout << "secret key: " << secret.string() << " (mode 0600, keep it on this machine)\n"
            << "public key: " << public_file.string() << "  " << pair.public_key << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& error) {
    std::cerr << "kapfix-keygen: " << error.what() << std::endl;
    return 1;
  }
}
