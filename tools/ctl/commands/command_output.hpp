#pragma once

// How kapfix-ctl speaks: errors on stderr with its name, result lines on stdout flushed at
// once (a script reading a pipe sees each line when it happens).

#include <string>

namespace kapfix::ctl {

// "kapfix-ctl: <text>" on stderr.
void Error(const std::string& text);

// One line on stdout, flushed.
void PrintLine(const std::string& line);

// "1.23": seconds with two decimals, for the summary lines.
std::string SecondsText(double seconds);

}  // namespace kapfix::ctl
