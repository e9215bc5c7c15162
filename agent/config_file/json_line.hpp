#pragma once

// Where a field of a JSON text is: protobuf's and nlohmann's parsers keep no positions of the
// values they read, so an error that names a field ("settings.gains.p") is placed by finding
// that field's keys in the text, one after the other.

#include <string_view>

namespace kapfix::agent {

// The 1-based line of the key of `dotted_path` ("servo.pan.max_deg"; an index such as
// "lenses[1]" finds the array's key) in `json_text`; 0 when a key is not found.
int JsonLineOf(std::string_view json_text, std::string_view dotted_path);

// The field an error reason starts with: the text before its first ": " or " = "
// ("settings.gains.p = 11: must be …" → "settings.gains.p"); empty when it has none.
std::string_view FieldOfReason(std::string_view reason);

}  // namespace kapfix::agent
