#include "tools/analyze/report_writer.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>

#include "common/io/atomic_file.hpp"

namespace kapfix::analyze {

ReportWriter::ReportWriter(std::string out_dir) : out_dir_(std::move(out_dir)) {
  if (out_dir_.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(out_dir_, ec);
  if (ec || !std::filesystem::is_directory(out_dir_)) {
    throw std::runtime_error("cannot create output folder '" + out_dir_ +
                             "': " + (ec ? ec.message() : "not a folder"));
  }
}

void ReportWriter::WriteAtomically(const std::string& name, const std::string& bytes) {
  if (!enabled()) return;
  const std::filesystem::path target = std::filesystem::path(out_dir_) / name;
  WriteFileAtomically(target, bytes);
  written_.push_back(target.string());
}

void ReportWriter::WriteCsv(const std::string& name, const std::vector<std::string>& header,
                            const std::vector<std::vector<double>>& columns) {
  if (!enabled()) return;
  if (header.size() != columns.size()) {
    throw std::logic_error("CSV '" + name + "': header and columns differ in count");
  }
  std::ostringstream csv;
  for (std::size_t c = 0; c < header.size(); ++c) csv << (c ? "," : "") << header[c];
  csv << '\n';
  std::size_t rows = 0;
  for (const auto& column : columns) rows = std::max(rows, column.size());
  csv.precision(10);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c) csv << ',';
      if (r < columns[c].size()) csv << columns[c][r];
    }
    csv << '\n';
  }
  WriteAtomically(name, csv.str());
}

void ReportWriter::WritePng(const std::string& name, const cv::Mat& image) {
  if (!enabled()) return;
  std::vector<unsigned char> png;
  if (!cv::imencode(".png", image, png)) {
    throw std::runtime_error("cannot encode PNG '" + name + "'");
  }
  WriteAtomically(name, std::string(png.begin(), png.end()));
}

void ReportWriter::WriteJson(const std::string& name, const nlohmann::json& json) {
  WriteAtomically(name, json.dump(2) + "\n");
}

void ReportWriter::WriteText(const std::string& name, const std::string& text) {
  WriteAtomically(name, text);
}

}  // namespace kapfix::analyze
