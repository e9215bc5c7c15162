#include "tools/ctl/photo_saving.hpp"

#include <system_error>

#include "common/io/atomic_file.hpp"
#include "kapfix/v1/photo_sidecar.hpp"

namespace kapfix::link {

bool PrepareSaveFolder(const std::filesystem::path& folder, std::string* error) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) {
    if (error) *error = "cannot create folder '" + folder.string() + "': " + ec.message();
    return false;
  }
  if (!std::filesystem::is_directory(folder, ec)) {
    if (error) *error = "'" + folder.string() + "' is not a folder";
    return false;
  }
  return true;
}

std::filesystem::path SavePhotoWithSidecar(const AssembledPhoto& photo,
                                           const std::filesystem::path& folder) {
  // Before the photo: metadata that cannot be written leaves nothing behind.
  const std::string sidecar = kapfix::v1::PhotoSidecarJson(photo.metadata);
  std::filesystem::path path = PhotoAssembler::Save(photo, folder);
  std::filesystem::path sidecar_path = path;
  sidecar_path += ".json";
  try {
    WriteFileAtomically(sidecar_path, sidecar);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    throw;
  }
  return path;
}

}  // namespace kapfix::link
