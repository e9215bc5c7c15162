#include "agent/server/intake_binding.hpp"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace kapfix::agent {

IntakeBinding::~IntakeBinding() { Close(); }

std::string IntakeBinding::Bind(zmq::socket_t& socket, const link::LinkEndpoint& endpoint,
                                const std::optional<link::BoundedIntakeOptions>& intake,
                                std::size_t max_connections, const std::string& what) {
  Close();
  if (!intake || endpoint.canonical.rfind("tcp://", 0) != 0) {
    socket.bind(endpoint.canonical);
    return socket.get(zmq::sockopt::last_endpoint);
  }
  // mkdtemp makes the directory 0700: no other user can reach the socket behind the intake.
  const char* base = std::getenv("XDG_RUNTIME_DIR");
  std::string pattern =
      std::string(base != nullptr && *base != '\0' ? base : "/tmp") + "/kapfix-intake-XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (::mkdtemp(buffer.data()) == nullptr) {
    throw std::runtime_error(
        what + ": cannot make a private directory for its intake: " + std::strerror(errno));
  }
  directory_ = buffer.data();
  path_ = directory_ + "/socket";
  link::BoundedIntakeOptions options = *intake;
  options.public_endpoint = endpoint.canonical;
  options.private_path = path_;
  options.max_connections = max_connections;
  options.what = what + " intake";
  try {
    socket.bind("ipc://" + path_);
    intake_ = std::make_unique<link::BoundedIntake>(options);
    return intake_->Start();
  } catch (...) {
    Close();
    throw;
  }
}

void IntakeBinding::Close() {
  if (intake_) intake_->Stop();
  intake_.reset();
  if (!path_.empty()) ::unlink(path_.c_str());
  if (!directory_.empty()) ::rmdir(directory_.c_str());
  path_.clear();
  directory_.clear();
}

void IntakeBinding::Consumed(const link::ReceivedWire& wire) const {
  if (intake_ && wire.source_fd >= 0) intake_->Consumed(wire.source_fd, wire.bytes);
}

void IntakeBinding::Disconnect(int fd) const {
  if (fd < 0) return;
  if (intake_) intake_->Disconnect(fd);
  ::shutdown(fd, SHUT_RDWR);
}

void IntakeBinding::Hold(int fd, std::chrono::steady_clock::time_point until) const {
  if (intake_ && fd >= 0) intake_->Hold(fd, until);
}

std::string IntakeBinding::PeerAddressOf(int fd) const {
  return intake_ ? intake_->PeerAddressOf(fd) : std::string();
}

link::BoundedIntake::Counters IntakeBinding::counters() const {
  return intake_ ? intake_->counters() : link::BoundedIntake::Counters{};
}

}  // namespace kapfix::agent
