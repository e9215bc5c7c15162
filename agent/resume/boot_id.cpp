#include "agent/resume/boot_id.hpp"

#include <random>

namespace kapfix::agent {

std::uint64_t DrawBootId() {
  std::random_device device;
  std::uint64_t id = 0;
  while (id == 0) {
    // random_device gives 32 bits a call.
    id = (static_cast<std::uint64_t>(device()) << 32U) | static_cast<std::uint64_t>(device());
  }
  return id;
}

}  // namespace kapfix::agent
