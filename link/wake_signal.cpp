#include "link/wake_signal.hpp"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <system_error>

namespace kapfix::link {

WakeSignal::WakeSignal() : fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  if (fd_ < 0) throw std::system_error(errno, std::generic_category(), "eventfd");
}

WakeSignal::~WakeSignal() { ::close(fd_); }

void WakeSignal::Notify() {
  const std::uint64_t one = 1;
  // Fails only when the counter would overflow (2^64 - 2 notifications not yet cleared), in
  // which case the fd is readable anyway: nothing to handle.
  (void)!::write(fd_, &one, sizeof one);
}

void WakeSignal::Clear() {
  std::uint64_t count = 0;
  (void)!::read(fd_, &count, sizeof count);  // EAGAIN when not notified: fine
}

}  // namespace kapfix::link
