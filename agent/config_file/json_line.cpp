#include "agent/config_file/json_line.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace kapfix::agent {
namespace {

// The position of `"key"` used as a key (followed by a colon) at or after `from`.
std::size_t FindKey(std::string_view text, std::string_view key, std::size_t from) {
  const std::string quoted = "\"" + std::string(key) + "\"";
  for (std::size_t at = text.find(quoted, from); at != std::string_view::npos;
       at = text.find(quoted, at + 1)) {
    std::size_t after = at + quoted.size();
    while (after < text.size() && std::isspace(static_cast<unsigned char>(text[after]))) ++after;
    if (after < text.size() && text[after] == ':') return at;
  }
  return std::string_view::npos;
}

}  // namespace

int JsonLineOf(std::string_view json_text, std::string_view dotted_path) {
  if (dotted_path.empty()) return 0;
  std::size_t position = 0;
  std::size_t start = 0;
  while (start <= dotted_path.size()) {
    std::size_t end = dotted_path.find('.', start);
    if (end == std::string_view::npos) end = dotted_path.size();
    std::string_view key = dotted_path.substr(start, end - start);
    key = key.substr(0, key.find('['));
    position = FindKey(json_text, key, position);
    if (position == std::string_view::npos) return 0;
    start = end + 1;
  }
  return 1 +
         static_cast<int>(std::count(
             json_text.begin(), json_text.begin() + static_cast<std::ptrdiff_t>(position), '\n'));
}

std::string_view FieldOfReason(std::string_view reason) {
  const std::size_t end = std::min(reason.find(": "), reason.find(" = "));
  if (end == std::string_view::npos) return {};
  const std::string_view field = reason.substr(0, end);
  const bool one_word = std::all_of(field.begin(), field.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.' || ch == '[' ||
           ch == ']';
  });
  return one_word ? field : std::string_view{};
}

}  // namespace kapfix::agent
