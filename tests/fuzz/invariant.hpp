#pragma once

// How the fuzz entry points report a broken promise: a message on stderr and std::abort(), which
// libFuzzer reports as a crash (keeping the input) and which fails the corpus replay test.

#include <cstdio>
#include <cstdlib>
#include <string>

namespace kapfix::fuzz {

[[noreturn]] inline void Broken(const std::string& what) {
  std::fprintf(stderr, "kapfix fuzz: invariant broken: %s\n", what.c_str());
  std::abort();
}

inline void Require(bool holds, const char* what) {
  if (!holds) Broken(what);
}

}  // namespace kapfix::fuzz
