#include "tools/ctl/commands/command_output.hpp"

#include <array>
#include <cstdio>
#include <iostream>

namespace kapfix::ctl {

void Error(const std::string& text) { std::cerr << "kapfix-ctl: " << text << std::endl; }

void PrintLine(const std::string& line) {
  std::fwrite(line.data(), 1, line.size(), stdout);
  std::fputc('\n', stdout);
  std::fflush(stdout);
}

std::string SecondsText(double seconds) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%.2f", seconds);
  return text.data();
}

}  // namespace kapfix::ctl
