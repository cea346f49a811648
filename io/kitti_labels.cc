#include "io/kitti_labels.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace attend {

namespace {

// The numbers of a label line after its type, in the devkit's order.
enum LabelValue {
  kTruncated,
  kOccluded,
  kAlpha,
  kLeft,
  kTop,
  kRight,
  kBottom,
  kH,
  kW,
  kL,
  kX,
  kY,
  kZ,
  kRotationY,
  kScore
};

KittiLabel ParseLabel(const std::vector<std::string>& words, const std::string& where) {
  if (words.size() != 17 && words.size() != 18) {
    throw InputError(where + ": " + std::to_string(words.size()) +
                     " values, but a tracking label has 17 (18 with a score)");
  }
  std::vector<double> values;
  for (size_t i = 0; i < words.size(); ++i) {
    if (i == 2) continue;  // the type
    char* end = nullptr;
    const double value = std::strtod(words[i].c_str(), &end);
    if (*end != '\0' || !std::isfinite(value)) {
      throw InputError(where + ": value " + std::to_string(i + 1) + " ('" + words[i] +
                       "') is not a number");
    }
    values.push_back(value);
  }
  // Whole numbers in int's range first: a cast of anything else is undefined.
  auto whole = [](double v) { return std::abs(v) < 1e9 && v == std::floor(v); };
  const double* v = values.data() + 2;
  if (!whole(values[0]) || !whole(values[1]) || values[0] < 0 || !whole(v[kOccluded])) {
    throw InputError(where + ": the frame, track id and occluded flag must be whole numbers, "
                     "the frame >= 0");
  }
  KittiLabel label;
  label.frame = static_cast<int>(values[0]);
  label.track_id = static_cast<int>(values[1]);
  label.type = words[2];
  label.truncated = v[kTruncated];
  label.occluded = static_cast<int>(v[kOccluded]);
  label.alpha = v[kAlpha];
  if (v[kRight] < v[kLeft] || v[kBottom] < v[kTop]) {
    throw InputError(where + ": the box's right or bottom is before its left or top");
  }
  label.box = cv::Rect2d(v[kLeft], v[kTop], v[kRight] - v[kLeft], v[kBottom] - v[kTop]);
  label.h = v[kH];
  label.w = v[kW];
  label.l = v[kL];
  label.location = cv::Vec3d(v[kX], v[kY], v[kZ]);
  label.rotation_y = v[kRotationY];
  if (words.size() == 18) label.score = v[kScore];
  return label;
}

}  // namespace

std::vector<KittiLabel> ReadKittiTrackingLabels(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the tracking labels");
  std::vector<KittiLabel> labels;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream stream(line);
    std::vector<std::string> words;
    std::string word;
    while (stream >> word) words.push_back(word);
    if (words.empty()) continue;
    labels.push_back(ParseLabel(words, path + " line " + std::to_string(line_number)));
  }
  return labels;
}

std::vector<cv::Vec4f> ReadVelodyneScan(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path + ": cannot read the Velodyne scan");
  const std::streamoff bytes = in.tellg();
  if (bytes < 0 || bytes % static_cast<std::streamoff>(sizeof(cv::Vec4f)) != 0) {
    throw InputError(path + ": " + std::to_string(bytes) +
                     " bytes, not a whole number of points (16 bytes each: float32 x y z "
                     "reflectance)");
  }
  std::vector<cv::Vec4f> points(static_cast<size_t>(bytes) / sizeof(cv::Vec4f));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(points.data()), bytes);
  if (!in) throw InputError(path + ": the Velodyne scan could not be read whole");
  return points;
}

}  // namespace attend
