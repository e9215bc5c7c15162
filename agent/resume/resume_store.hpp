#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "agent/resume/resume_record.hpp"

namespace kapfix::agent {

// The ResumeRecord on disk, in the agent's state folder (issue 14): `resume.json` (settings
// commands as protobuf JSON, mode, slice, where the reference was taken) and the reference
// frame as a lossless PNG next to it. Both are written with WriteFileAtomically, the image
// first under a new name and the JSON naming it last, so a crash at any point leaves the
// previous record or the new one, never a mix. Not thread-safe: one writer.
class ResumeStore {
 public:
  explicit ResumeStore(std::filesystem::path dir);

  // Throws std::runtime_error naming the file and the reason (full disk, no permission).
  void Save(const ResumeRecord& record);
  // The stored record. Nothing stored: nullopt with `error` empty. A file that cannot be used
  // (not JSON, truncated, a field of the wrong type, an unknown mode, a command that does not
  // parse, a missing or unreadable reference image): nullopt with the reason naming the file.
  std::optional<ResumeRecord> Load(std::string* error);
  // Moves an unusable resume.json aside (resume.json.bad, replacing an older one) so that it
  // stays for a look but is not read again; the new path, or empty when it could not move.
  std::filesystem::path SetAside() const;

  std::filesystem::path file() const { return dir_ / "resume.json"; }

 private:
  std::filesystem::path dir_;
  // The reference image the stored JSON names: a record holding the same frame (its pixels
  // shared) does not write it again.
  cv::Mat written_reference_;
  std::string written_reference_name_;
};

}  // namespace kapfix::agent
