#include "kapfix/v1/photo_sidecar.hpp"

#include <google/protobuf/util/json_util.h>

#include <stdexcept>

namespace kapfix::v1 {

std::string PhotoSidecarJson(const PhotoMetadata& metadata) {
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.preserve_proto_field_names = true;
  // Every quality field, also a false lock_lost or a 0 px blur: to a reader that does not
  // know proto3's defaults, a missing one would read as "not measured".
  options.always_print_primitive_fields = true;
  if (!google::protobuf::util::MessageToJsonString(metadata, &json, options).ok()) {
    throw std::runtime_error("photo " + metadata.file_name() +
                             ": metadata not representable as JSON");
  }
  return json;
}

}  // namespace kapfix::v1
