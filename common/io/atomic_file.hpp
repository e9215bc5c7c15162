#pragma once

#include <filesystem>
#include <string_view>

namespace kapfix {

// Writes `bytes` to `target` through a temporary file in the same folder, fsync and a rename, so a
// reader never sees a half-written file and a failed write (full disk, no permission) leaves
// neither a partial file nor the temporary behind. Throws std::runtime_error naming the file
// and the reason.
void WriteFileAtomically(const std::filesystem::path& target, std::string_view bytes);

}  // namespace kapfix
