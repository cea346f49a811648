#include "tests/support/stereo_pair_maker.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace attend::testing {

cv::Mat TexturedImage(cv::Size size, std::uint64_t seed) {
  cv::Mat noise(size, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, cv::Scalar::all(0), cv::Scalar::all(256));
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 1.2);
  // Blocks of colour give corners at several scales.
  for (int i = 0; i < size.area() / 2000; ++i) {
    const cv::Point corner(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const cv::Size side(rng.uniform(6, 40), rng.uniform(6, 40));
    const cv::Scalar colour(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256));
    cv::rectangle(noise, cv::Rect(corner, side), colour, cv::FILLED);
  }
  return noise;
}

cv::Mat ShiftDown(const cv::Mat& image, double rows) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 0, 0, 1, rows);
  cv::Mat out;
  cv::warpAffine(image, out, shift, image.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

cv::Mat Rotate(const cv::Mat& image, double degrees) {
  const cv::Point2f centre((image.cols - 1) / 2.0f, (image.rows - 1) / 2.0f);
  cv::Mat out;
  cv::warpAffine(image, out, cv::getRotationMatrix2D(centre, degrees, 1.0), image.size(),
                 cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

KnownPair MakeKnownPair(cv::Size size, double disparity, std::uint64_t seed) {
  KnownPair pair;
  StereoCalibration& c = pair.calibration;
  c.form = StereoCalibration::Form::kFull;
  c.image_size = size;
  c.source = "a known pair";
  const double f = 0.9 * size.width;
  c.K1 = (cv::Mat_<double>(3, 3) << f, 0, (size.width - 1) / 2.0 + 3.0, 0, f,
          (size.height - 1) / 2.0 - 2.0, 0, 0, 1);
  c.K2 = (cv::Mat_<double>(3, 3) << f * 1.01, 0, (size.width - 1) / 2.0 - 4.0, 0, f * 1.01,
          (size.height - 1) / 2.0 + 5.0, 0, 0, 1);
  c.D1 = cv::Mat::zeros(1, 5, CV_64F);
  c.D2 = cv::Mat::zeros(1, 5, CV_64F);
  const cv::Mat rotation = (cv::Mat_<double>(3, 1) << 0.012, -0.02, 0.03);  // radians
  cv::Rodrigues(rotation, c.R);
  c.T = (cv::Mat_<double>(3, 1) << -0.12, 0.004, 0.002);
  cv::stereoRectify(c.K1, c.D1, c.K2, c.D2, size, c.R, c.T, c.R1, c.R2, c.P1, c.P2, c.Q,
                    cv::CALIB_ZERO_DISPARITY, 0.0);
  // The rectified views of a plane parallel to them: the right is the left moved along rows.
  const cv::Size wide(size.width + static_cast<int>(disparity) + 2, size.height);
  const cv::Mat texture = TexturedImage(wide, seed);
  const cv::Mat along = (cv::Mat_<double>(2, 3) << 1, 0, disparity, 0, 1, 0);
  pair.rectified_left = texture(cv::Rect(cv::Point(0, 0), size)).clone();
  cv::warpAffine(texture, pair.rectified_right, along, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  // A raw pixel p of camera k shows the rectified pixel H_k p, H_k = P_k(:, 0:3) R_k K_k^-1.
  const auto raw = [&](const cv::Mat& rectified, const cv::Mat& P, const cv::Mat& R,
                       const cv::Mat& K) {
    const cv::Mat H = P(cv::Rect(0, 0, 3, 3)) * R * K.inv();
    cv::Mat out;
    cv::warpPerspective(rectified, out, H, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                        cv::BORDER_REPLICATE);
    return out;
  };
  pair.raw_left = raw(pair.rectified_left, c.P1, c.R1, c.K1);
  pair.raw_right = raw(pair.rectified_right, c.P2, c.R2, c.K2);
  return pair;
}

}  // namespace attend::testing
