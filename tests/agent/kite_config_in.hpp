#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "agent/config/agent_config.hpp"
#include "agent/config_file/agent_config_file.hpp"

namespace kapfix::agent {

// resources/kite.json as shipped (its lenses defined by their optics), in simulation, with its
// own state and photo folders and a private ipc:// link, all in `base` (created).
inline AgentConfig KiteConfigIn(const std::filesystem::path& base) {
  std::filesystem::create_directories(base);  // the link's ipc files live there
  AgentConfig config;
  std::string error;
  EXPECT_TRUE(LoadAgentConfig(std::string(KAPFIX_RESOURCES_DIR) + "/kite.json", &config, &error))
      << error;
  config.state_dir = (base / "state").string();
  config.photos.dir = (base / "photos").string();
  config.link.command_address = "ipc://" + (base / "cmd").string();
  config.link.stream_address = "ipc://" + (base / "stream").string();
  config.link.curve_secret_key_file.clear();
  config.link.curve_authorized_keys_file.clear();
  return config;
}

}  // namespace kapfix::agent
