#include "io/calibration_text.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace attend {

namespace {

// Parses `word` as a whole number; false for anything else ("1.2x", "nan" parses but is caught
// by the finiteness check of Numbers).
bool ParseNumber(const std::string& word, double* value) {
  char* end = nullptr;
  *value = std::strtod(word.c_str(), &end);
  return end != word.c_str() && *end == '\0';
}

}  // namespace

CalibrationText::CalibrationText(const std::string& path) : path_(path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the calibration file");
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string key;
    if (!(words >> key)) continue;
    std::string rest;
    const size_t colon = key.find(':');
    if (colon != std::string::npos) {
      // "P2:" or "calib_time:09-Jan..." : the key ends at the colon.
      rest = key.substr(colon + 1);
      key.resize(colon);
    }
    Entry entry;
    entry.line = line_number;
    std::string tail;
    std::getline(words, tail);
    std::istringstream values(rest + " " + tail);
    std::string word;
    while (values >> word) {
      double value = 0.0;
      if (!ParseNumber(word, &value)) {
        if (entry.bad_word.empty()) entry.bad_word = word;
        continue;
      }
      entry.numbers.push_back(value);
    }
    entries_[key] = entry;
  }
}

std::vector<double> CalibrationText::Numbers(const std::string& key, size_t count) const {
  const auto it = entries_.find(key);
  if (it == entries_.end()) throw InputError(path_ + ": " + key + " is missing");
  const Entry& entry = it->second;
  const std::string where = path_ + " line " + std::to_string(entry.line) + ": " + key;
  if (!entry.bad_word.empty()) {
    throw InputError(where + " has '" + entry.bad_word + "' where a number should be");
  }
  if (entry.numbers.size() != count) {
    throw InputError(where + " must hold " + std::to_string(count) + " numbers, got " +
                     std::to_string(entry.numbers.size()));
  }
  for (double v : entry.numbers) {
    if (!std::isfinite(v)) throw InputError(where + " has a value that is not finite");
  }
  return entry.numbers;
}

cv::Mat CalibrationText::Matrix(const std::string& key, int rows, int cols) const {
  const std::vector<double> numbers = Numbers(key, static_cast<size_t>(rows * cols));
  return cv::Mat(rows, cols, CV_64F, const_cast<double*>(numbers.data())).clone();
}

std::string CalibrationText::FirstOf(const std::vector<std::string>& keys) const {
  for (const std::string& key : keys) {
    if (Has(key)) return key;
  }
  return "";
}

StereoCalibration RectifiedFromProjections(const std::string& source, const cv::Mat& left,
                                           const cv::Mat& right, cv::Size size) {
  if (size.width < 1 || size.height < 1) {
    throw InputError(source + ": the image size is not known (give --size WxH)");
  }
  StereoCalibration c;
  c.form = StereoCalibration::Form::kRectified;
  c.source = source;
  c.image_size = size;
  c.P1 = left.clone();
  c.P1.col(3).setTo(0.0);
  c.P2 = right.clone();
  c.P2.col(3) = right.col(3) - left.col(3);
  if (c.P1.at<double>(0, 0) <= 0 || c.P2.at<double>(0, 0) <= 0) {
    throw InputError(source + ": the focal length is not positive");
  }
  if (!(c.baseline_m() > 0)) {
    throw InputError(source +
                     ": the right camera is not to the right of the left one "
                     "(baseline " +
                     std::to_string(c.baseline_m()) + " m)");
  }
  // Q and the identity rectifications as the reader makes them.
  StereoCalibration nominal = NominalCalibration(c.focal_px(), c.baseline_m(), size, c.source);
  c.R1 = nominal.R1;
  c.R2 = nominal.R2;
  c.Q = nominal.Q;
  c.Q.at<double>(0, 3) = -c.cx();
  c.Q.at<double>(1, 3) = -c.cy();
  c.Q.at<double>(3, 3) = (c.cx() - c.P2.at<double>(0, 2)) / (-c.baseline_m());
  return c;
}

}  // namespace attend
