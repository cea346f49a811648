#include "io/stereo_calibration.h"

#include <cmath>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "util/error.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

// "ROWSxCOLS", for messages.
std::string Describe(const cv::Mat& m) {
  return std::to_string(m.rows) + "x" + std::to_string(m.cols);
}

// Reads one file of calibration keys, and says which file and key when something is wrong.
class CalibrationReader {
 public:
  explicit CalibrationReader(const std::string& path) : path_(path) {
    std::error_code error;
    if (!fs::exists(path, error)) throw InputError(path + ": no such calibration file");
    if (!fs::is_regular_file(path, error)) throw InputError(path + ": not a file");
    try {
      storage_.open(path, cv::FileStorage::READ | cv::FileStorage::FORMAT_AUTO);
    } catch (const cv::Exception& e) {
      throw InputError(path + ": not an OpenCV FileStorage calibration (YAML, XML or JSON): " +
                       e.err);
    }
    if (!storage_.isOpened() || !storage_.root().isMap()) {
      throw InputError(path + ": not an OpenCV FileStorage calibration (YAML, XML or JSON)");
    }
  }

  bool Has(const std::string& key) const { return !storage_[key].empty(); }

  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    throw InputError(path_ + ": " + key + " " + what);
  }

  // The matrix `key` (or its synonym), CV_64F, `rows` x `cols` (cols -1: a row or column
  // vector of any of `lengths`); every value finite.
  cv::Mat Matrix(const std::string& key, int rows, int cols, const std::string& synonym = "",
                 const std::vector<int>& lengths = {}) const {
    std::string name = key;
    if (!Has(key) && !synonym.empty() && Has(synonym)) name = synonym;
    if (!Has(name)) {
      Fail(key, synonym.empty() ? "is missing" : "(or " + synonym + ") is missing");
    }
    cv::Mat m;
    try {
      storage_[name] >> m;
    } catch (const cv::Exception& e) {
      Fail(name, "is not a matrix (!!opencv-matrix): " + e.err);
    }
    if (m.empty() || m.channels() != 1) Fail(name, "is not a one-channel matrix");
    m.convertTo(m, CV_64F);
    if (cols < 0) {
      const int length = static_cast<int>(m.total());
      const bool vector = m.rows == 1 || m.cols == 1;
      bool allowed = false;
      for (int l : lengths) allowed = allowed || l == length;
      if (!vector || !allowed) {
        std::string expected;
        for (int l : lengths) expected += (expected.empty() ? "" : ", ") + std::to_string(l);
        Fail(name, "must be a vector of " + expected + " coefficients, got " + Describe(m));
      }
      m = m.reshape(1, 1).clone();
    } else if (m.rows != rows || m.cols != cols) {
      if (rows * cols == 3 && m.total() == 3 && (m.rows == 1 || m.cols == 1)) {
        m = m.reshape(1, 3).clone();  // T as a row or a column
      } else {
        Fail(name, "must be " + std::to_string(rows) + "x" + std::to_string(cols) + ", got " +
                       Describe(m));
      }
    }
    if (!cv::checkRange(m)) Fail(name, "has a value that is not finite");
    return m;
  }

  double Number(const std::string& key) const {
    const cv::FileNode node = storage_[key];
    if (!node.isReal() && !node.isInt()) Fail(key, "must be a number");
    const double value = static_cast<double>(node);
    if (!std::isfinite(value)) Fail(key, "is not finite");
    return value;
  }

  // image_width and image_height (as OpenCV's calibration sample writes them), or image_size
  // [width, height].
  cv::Size ImageSize() const {
    if (Has("image_width") || Has("image_height")) {
      const double width = Number("image_width");
      const double height = Number("image_height");
      if (width < 1 || height < 1 || width != std::floor(width) || height != std::floor(height)) {
        Fail("image_width", "and image_height must be positive whole numbers");
      }
      return {static_cast<int>(width), static_cast<int>(height)};
    }
    if (Has("image_size")) {
      std::vector<int> size;
      try {
        storage_["image_size"] >> size;
      } catch (const cv::Exception&) {
      }
      if (size.size() != 2 || size[0] < 1 || size[1] < 1) {
        Fail("image_size", "must be [width, height], both positive");
      }
      return {size[0], size[1]};
    }
    Fail("image_width", "(with image_height) is missing: the native frame size is required");
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  cv::FileStorage storage_;
};

// The disparity-to-depth map of rectified cameras P1, P2 (as cv::stereoRectify makes it).
cv::Mat DisparityToDepth(const cv::Mat& P1, const cv::Mat& P2) {
  const double f = P1.at<double>(0, 0);
  const double cx = P1.at<double>(0, 2), cy = P1.at<double>(1, 2);
  const double cx_right = P2.at<double>(0, 2);
  const double tx = P2.at<double>(0, 3) / P2.at<double>(0, 0);  // -baseline
  cv::Mat Q = cv::Mat::zeros(4, 4, CV_64F);
  Q.at<double>(0, 0) = 1.0;
  Q.at<double>(0, 3) = -cx;
  Q.at<double>(1, 1) = 1.0;
  Q.at<double>(1, 3) = -cy;
  Q.at<double>(2, 3) = f;
  Q.at<double>(3, 2) = -1.0 / tx;
  Q.at<double>(3, 3) = (cx - cx_right) / tx;
  return Q;
}

// The checks every form shares: focal lengths, a horizontal baseline that is not zero.
void CheckProjections(const CalibrationReader& file, const StereoCalibration& c) {
  for (const auto& [name, P] : {std::pair<const char*, const cv::Mat*>{"P1", &c.P1}, {"P2", &c.P2}}) {
    if (P->at<double>(0, 0) <= 0 || P->at<double>(1, 1) <= 0) {
      file.Fail(name, "has a focal length that is not positive (" +
                          std::to_string(P->at<double>(0, 0)) + ", " +
                          std::to_string(P->at<double>(1, 1)) + ")");
    }
  }
  const double tx = c.P2.at<double>(0, 3);
  const double ty = c.P2.at<double>(1, 3);
  if (std::abs(ty) > std::abs(tx)) {
    file.Fail("P2", "is a vertical pair's (P2(1,3) is not zero); attend reads side-by-side pairs");
  }
  if (tx == 0.0) file.Fail("P2", "has a zero baseline (P2(0,3) = 0)");
  if (tx > 0.0) {
    file.Fail("P2", "puts the right camera to the left of the left one (P2(0,3) > 0): are the "
                    "views swapped?");
  }
}

void ReadFull(const CalibrationReader& file, StereoCalibration* c) {
  c->form = StereoCalibration::Form::kFull;
  const std::vector<int> distortion = {4, 5, 8, 12, 14};
  c->K1 = file.Matrix("K1", 3, 3, "M1");
  c->D1 = file.Matrix("D1", 1, -1, "", distortion);
  c->K2 = file.Matrix("K2", 3, 3, "M2");
  c->D2 = file.Matrix("D2", 1, -1, "", distortion);
  c->R = file.Matrix("R", 3, 3);
  c->T = file.Matrix("T", 3, 1);
  for (const auto& [name, K] :
       {std::pair<const char*, const cv::Mat*>{"K1", &c->K1}, {"K2", &c->K2}}) {
    if (K->at<double>(0, 0) <= 0 || K->at<double>(1, 1) <= 0) {
      file.Fail(name, "has a focal length that is not positive");
    }
  }
  if (cv::norm(c->T) == 0.0) file.Fail("T", "is zero: the baseline must not be");
  const bool rectified = file.Has("R1") || file.Has("R2") || file.Has("P1") ||
                         file.Has("P2") || file.Has("Q");
  if (rectified) {
    c->R1 = file.Matrix("R1", 3, 3);
    c->R2 = file.Matrix("R2", 3, 3);
    c->P1 = file.Matrix("P1", 3, 4);
    c->P2 = file.Matrix("P2", 3, 4);
    c->Q = file.Has("Q") ? file.Matrix("Q", 4, 4) : DisparityToDepth(c->P1, c->P2);
  } else {
    cv::stereoRectify(c->K1, c->D1, c->K2, c->D2, c->image_size, c->R, c->T, c->R1, c->R2, c->P1,
                      c->P2, c->Q, cv::CALIB_ZERO_DISPARITY, 0.0);
  }
}

void ReadRectified(const CalibrationReader& file, StereoCalibration* c) {
  c->form = StereoCalibration::Form::kRectified;
  c->P1 = file.Matrix("P1", 3, 4);
  c->P2 = file.Matrix("P2", 3, 4);
  c->R1 = cv::Mat::eye(3, 3, CV_64F);
  c->R2 = cv::Mat::eye(3, 3, CV_64F);
  CheckProjections(file, *c);
  c->Q = DisparityToDepth(c->P1, c->P2);
}

void WriteMatrix(cv::FileStorage* out, const char* key, const cv::Mat& m) {
  if (!m.empty()) *out << key << m;
}

}  // namespace

StereoCalibration ReadStereoCalibration(const std::string& path) {
  const CalibrationReader file(path);
  StereoCalibration c;
  c.source = path;
  c.image_size = file.ImageSize();
  const bool full = file.Has("K1") || file.Has("M1") || file.Has("K2") || file.Has("M2") ||
                    file.Has("D1") || file.Has("D2") || file.Has("R") || file.Has("T");
  if (full) {
    ReadFull(file, &c);
  } else if (file.Has("P1") || file.Has("P2")) {
    ReadRectified(file, &c);
  } else {
    file.Fail("K1", "(or M1) and P1 are both missing: a calibration holds K1, D1, K2, D2, R, T "
                    "(a raw pair) or P1 and P2 (a rectified pair)");
  }
  CheckProjections(file, c);
  if (file.Has("rms")) c.rms_px = file.Number("rms");
  return c;
}

void WriteStereoCalibration(const StereoCalibration& calibration, const std::string& path) {
  cv::FileStorage out;
  try {
    out.open(path, cv::FileStorage::WRITE | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& e) {
    throw OutputError(path + ": cannot write the calibration: " + e.err);
  }
  if (!out.isOpened()) throw OutputError(path + ": cannot write the calibration");
  const StereoCalibration& c = calibration;
  out << "image_width" << c.image_size.width << "image_height" << c.image_size.height;
  if (c.form == StereoCalibration::Form::kFull) {
    WriteMatrix(&out, "K1", c.K1);
    WriteMatrix(&out, "D1", c.D1);
    WriteMatrix(&out, "K2", c.K2);
    WriteMatrix(&out, "D2", c.D2);
    WriteMatrix(&out, "R", c.R);
    WriteMatrix(&out, "T", c.T);
    WriteMatrix(&out, "R1", c.R1);
    WriteMatrix(&out, "R2", c.R2);
  }
  WriteMatrix(&out, "P1", c.P1);
  WriteMatrix(&out, "P2", c.P2);
  if (c.form == StereoCalibration::Form::kFull) WriteMatrix(&out, "Q", c.Q);
  if (c.rms_px >= 0) out << "rms" << c.rms_px;
  out.release();
  std::error_code error;
  if (!fs::exists(path, error)) throw OutputError(path + ": cannot write the calibration");
}

StereoCalibration NominalCalibration(double focal_px, double baseline_m, cv::Size image_size,
                                     const std::string& source) {
  ATTEND_CHECK(focal_px > 0 && baseline_m > 0) << "a nominal calibration needs f and B > 0";
  StereoCalibration c;
  c.form = StereoCalibration::Form::kNominal;
  c.source = source;
  c.image_size = image_size;
  const double cx = (image_size.width - 1) / 2.0;
  const double cy = (image_size.height - 1) / 2.0;
  c.P1 = (cv::Mat_<double>(3, 4) << focal_px, 0, cx, 0, 0, focal_px, cy, 0, 0, 0, 1, 0);
  c.P2 = c.P1.clone();
  c.P2.at<double>(0, 3) = -focal_px * baseline_m;
  c.R1 = cv::Mat::eye(3, 3, CV_64F);
  c.R2 = cv::Mat::eye(3, 3, CV_64F);
  c.Q = DisparityToDepth(c.P1, c.P2);
  return c;
}

Rectifier::Rectifier(const StereoCalibration& calibration) : size_(calibration.image_size) {
  ATTEND_CHECK(calibration.rectifies()) << "only a full calibration rectifies";
  const StereoCalibration& c = calibration;
  cv::initUndistortRectifyMap(c.K1, c.D1, c.R1, c.P1, size_, CV_16SC2, left_x_, left_y_);
  cv::initUndistortRectifyMap(c.K2, c.D2, c.R2, c.P2, size_, CV_16SC2, right_x_, right_y_);
}

void Rectifier::Apply(cv::Mat* left, cv::Mat* right) const {
  for (const cv::Mat* view : {left, right}) {
    if (view->size() != size_) {
      throw InputError("a frame of " + std::to_string(view->cols) + "x" +
                       std::to_string(view->rows) + " cannot be rectified by a calibration for " +
                       std::to_string(size_.width) + "x" + std::to_string(size_.height));
    }
  }
  cv::Mat rectified;
  cv::remap(*left, rectified, left_x_, left_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  *left = rectified;
  cv::Mat rectified_right;
  cv::remap(*right, rectified_right, right_x_, right_y_, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  *right = rectified_right;
}

}  // namespace attend
