// Built without libsystemd: nothing to tell (the unit must then be Type=simple).
#include "agent/service/systemd_notifier.hpp"

namespace kapfix::agent {

SystemdNotifier::SystemdNotifier() = default;
void SystemdNotifier::Ready(const std::string& /*status*/) {}
void SystemdNotifier::Alive() {}
void SystemdNotifier::Status(const std::string& /*status*/) {}
void SystemdNotifier::Stopping() {}

}  // namespace kapfix::agent
