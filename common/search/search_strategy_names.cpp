#include "common/search/search_strategy_names.hpp"

namespace kapfix {

const std::vector<std::string>& SearchStrategyNames() {
  static const std::vector<std::string> names = {"all", "h23", "h21", "h19", "h17", "h15", "pyr"};
  return names;
}

}  // namespace kapfix
