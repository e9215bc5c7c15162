#pragma once

// Process-wide settings that decide what peers on the link can make the agent hold
// (issue 15, items 3 and 4). Called once at start, before the servers bind.

#include <cstdint>

namespace kapfix::link {

// Raises the soft limit on open file descriptors towards `wanted` (at most the hard limit) and
// returns the soft limit in force afterwards. The default soft limit (1,024) is what about 33
// new connections a second exhaust while libzmq holds each one through its handshake; a
// photo then fails with "Too many open files".
std::uint64_t RaiseOpenFileLimit(std::uint64_t wanted);

// Makes large receive buffers (a peer's message frames of 128 KiB and more) separate
// mappings that go back to the system when freed. glibc otherwise raises its mmap threshold
// after the first such free, so the memory of a refused or abandoned multipart message stays
// in the heap, counted in RSS, after the peer has gone.
void ReturnLargeBuffersWhenFreed();

}  // namespace kapfix::link
