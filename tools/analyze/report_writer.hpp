#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace kapfix::analyze {

// Writes a subcommand's CSV tables and PNG plots into --out DIR. Each file is written to a
// temporary name and renamed, so an interrupted run or a full disk never leaves a truncated
// file under the final name. Without an output folder nothing is written.
class ReportWriter {
 public:
  // Creates `out_dir` (and parents) when it is not empty; throws std::runtime_error naming the
  // folder and the reason when it cannot.
  explicit ReportWriter(std::string out_dir);

  bool enabled() const { return !out_dir_.empty(); }
  // Columns of equal length under their names.
  void WriteCsv(const std::string& name, const std::vector<std::string>& header,
                const std::vector<std::vector<double>>& columns);
  void WritePng(const std::string& name, const cv::Mat& image);
  void WriteJson(const std::string& name, const nlohmann::json& json);
  void WriteText(const std::string& name, const std::string& text);  // e.g. a Markdown report
  // Paths written so far, for the summary.
  const std::vector<std::string>& written() const { return written_; }

 private:
  void WriteAtomically(const std::string& name, const std::string& bytes);

  std::string out_dir_;
  std::vector<std::string> written_;
};

}  // namespace kapfix::analyze
