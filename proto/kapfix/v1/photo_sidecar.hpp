#pragma once

#include <string>

#include "kapfix/v1/photo.pb.h"

namespace kapfix::v1 {

// A photo's JSON sidecar: its PhotoMetadata as protobuf JSON with the .proto field names,
// indented, every field written (false and zero ones too). The agent's photo store,
// kapfix-ctl and the station write the same text. Throws
// std::runtime_error when the metadata is not representable (invalid UTF-8 in a string).
std::string PhotoSidecarJson(const PhotoMetadata& metadata);

}  // namespace kapfix::v1
