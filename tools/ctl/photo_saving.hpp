#pragma once

// Saving a received photo as the agent stores it: the image and, beside it, its JSON sidecar
// (issue 13: the sidecar carries the photo's quality), in a folder made when missing.

#include <filesystem>
#include <string>

#include "link/photo_assembler.hpp"

namespace kapfix::link {

// Makes `folder` (with its parents) when it does not exist; false with the reason when it
// cannot be made or is not a folder.
bool PrepareSaveFolder(const std::filesystem::path& folder, std::string* error);

// Writes folder/NAME (PhotoAssembler::Save) and folder/NAME.json, the metadata as the agent's
// photo store writes it (kapfix::v1::PhotoSidecarJson), each atomically. Returns the photo's
// path. Throws std::runtime_error naming the file; when the sidecar cannot be written the
// photo is removed again, so the folder only holds complete pairs (the agent keeps its copy).
std::filesystem::path SavePhotoWithSidecar(const AssembledPhoto& photo,
                                           const std::filesystem::path& folder);

}  // namespace kapfix::link
