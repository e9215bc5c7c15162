#pragma once

// The names of the search strategies, alone: the link's command validator checks a station's
// choice against them without needing the strategies themselves (or OpenCV).

#include <string>
#include <vector>

namespace kapfix {

// "all", "h23", "h21", "h19", "h17", "h15", "pyr": the names MakeSearchStrategy accepts.
const std::vector<std::string>& SearchStrategyNames();

}  // namespace kapfix
