#include "tests/support/kitti_maker.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace attend::testing {

namespace fs = std::filesystem;

namespace {

// P of a camera `offset_m` to the right of camera 0 (KITTI's last column, K t).
std::string Projection(const KittiTestRig& rig, double offset_m) {
  std::ostringstream out;
  out.precision(17);
  out << rig.focal << " 0 " << rig.cx << " " << -rig.focal * offset_m << " 0 " << rig.focal << " "
      << rig.cy << " 0 0 0 1 0";
  return out.str();
}

constexpr const char* kIdentity = "1 0 0 0 1 0 0 0 1";
constexpr const char* kVeloRotation = "0 -1 0 0 0 -1 1 0 0";

std::string Name(int index, int digits) {
  char name[32];
  std::snprintf(name, sizeof(name), "%0*d", digits, index);
  return name;
}

void WriteFrames(const fs::path& left_folder, const fs::path& right_folder, int digits,
                 const std::vector<cv::Mat>& left, const std::vector<cv::Mat>& right) {
  fs::create_directories(left_folder);
  fs::create_directories(right_folder);
  for (size_t i = 0; i < left.size(); ++i) {
    cv::imwrite((left_folder / (Name(static_cast<int>(i), digits) + ".png")).string(), left[i]);
    cv::imwrite((right_folder / (Name(static_cast<int>(i), digits) + ".png")).string(), right[i]);
  }
}

void WriteText(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

}  // namespace

std::string KittiTestRig::CamToCam() const {
  std::ostringstream out;
  out << "calib_time: 09-Jan-2012 13:57:47\ncorner_dist: 9.950000e-02\n"
      << "S_rect_00: " << size.width << " " << size.height << "\n"
      << "R_rect_00: " << kIdentity << "\nP_rect_00: " << Projection(*this, 0.0) << "\n"
      << "S_rect_02: " << size.width << " " << size.height << "\n"
      << "R_rect_02: " << kIdentity << "\nP_rect_02: " << Projection(*this, -0.06) << "\n"
      << "S_rect_03: " << size.width << " " << size.height << "\n"
      << "P_rect_03: " << Projection(*this, baseline - 0.06) << "\n";
  return out.str();
}

std::string KittiTestRig::VeloToCam() const {
  return std::string("calib_time: 15-Mar-2012 11:37:16\nR: ") + kVeloRotation +
         "\nT: 0 0 0\ndelta_f: 0 0\ndelta_c: 0 0\n";
}

std::string KittiTestRig::Tracking() const {
  return "P0: " + Projection(*this, 0.0) + "\nP1: " + Projection(*this, baseline) +
         "\nP2: " + Projection(*this, -0.06) + "\nP3: " + Projection(*this, baseline - 0.06) +
         "\nR_rect " + kIdentity + "\nTr_velo_cam 0 -1 0 0 0 0 -1 0 1 0 0 0\n" +
         "Tr_imu_velo 1 0 0 0 0 1 0 0 0 0 1 0\n";
}

std::string OneCarTracklet(int frames) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"yes\" ?>\n"
      << "<!DOCTYPE boost_serialization>\n"
      << "<boost_serialization signature=\"serialization::archive\" version=\"9\">\n"
      << "<tracklets class_id=\"0\" tracking_level=\"0\" version=\"0\">\n"
      << "\t<count>1</count>\n\t<item_version>1</item_version>\n"
      << "\t<item class_id=\"1\" tracking_level=\"0\" version=\"1\">\n"
      << "\t\t<objectType>Car</objectType>\n\t\t<h>1.5</h>\n\t\t<w>2</w>\n\t\t<l>4</l>\n"
      << "\t\t<first_frame>0</first_frame>\n"
      << "\t\t<poses class_id=\"2\" tracking_level=\"0\" version=\"0\">\n"
      << "\t\t\t<count>" << frames << "</count>\n\t\t\t<item_version>2</item_version>\n";
  for (int i = 0; i < frames; ++i) {
    out << "\t\t\t<item class_id=\"3\" tracking_level=\"0\" version=\"2\">\n"
        << "\t\t\t\t<tx>10</tx>\n\t\t\t\t<ty>0</ty>\n\t\t\t\t<tz>-1.73</tz>\n"
        << "\t\t\t\t<rx>0</rx>\n\t\t\t\t<ry>0</ry>\n\t\t\t\t<rz>0</rz>\n"
        << "\t\t\t\t<state>2</state>\n\t\t\t\t<occlusion>0</occlusion>\n"
        << "\t\t\t\t<occlusion_kf>1</occlusion_kf>\n\t\t\t\t<truncation>0</truncation>\n"
        << "\t\t\t\t<amt_occlusion>0.0</amt_occlusion>\n"
        << "\t\t\t\t<amt_occlusion_kf>-1</amt_occlusion_kf>\n"
        << "\t\t\t\t<amt_border_l>0.0</amt_border_l>\n\t\t\t\t<amt_border_r>0.0</amt_border_r>\n"
        << "\t\t\t\t<amt_border_kf>-1</amt_border_kf>\n\t\t\t</item>\n";
  }
  out << "\t\t</poses>\n\t\t<finished>1</finished>\n\t</item>\n</tracklets>\n"
      << "</boost_serialization>\n";
  return out.str();
}

std::vector<cv::Vec4f> FlatGroundScan() {
  std::vector<cv::Vec4f> scan;
  for (int x = 4; x <= 20; ++x) {
    for (int y = -4; y <= 4; ++y) scan.emplace_back(x, y, -1.73f, 0.5f);
  }
  for (float y : {-0.5f, 0.f, 0.5f}) {
    for (float z : {-1.2f, -0.8f, -0.4f}) scan.emplace_back(8.f, y, z, 0.9f);
  }
  scan.emplace_back(-5.f, 0.f, -1.73f, 0.1f);
  scan.emplace_back(-8.f, 2.f, 0.f, 0.1f);
  return scan;
}

void WriteScan(const std::string& path, const std::vector<cv::Vec4f>& scan) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(scan.data()),
            static_cast<std::streamsize>(scan.size() * sizeof(cv::Vec4f)));
}

std::string WriteKittiRawDrive(const TempDir& dir, const KittiTestRig& rig,
                               const std::vector<cv::Mat>& left,
                               const std::vector<cv::Mat>& right) {
  const fs::path date = dir.path() / "2011_09_26";
  const fs::path drive = date / "2011_09_26_drive_0001_sync";
  WriteFrames(drive / "image_02" / "data", drive / "image_03" / "data", 10, left, right);
  WriteText(date / "calib_cam_to_cam.txt", rig.CamToCam());
  WriteText(date / "calib_velo_to_cam.txt", rig.VeloToCam());
  WriteText(drive / "tracklet_labels.xml", OneCarTracklet(static_cast<int>(left.size())));
  for (size_t i = 0; i < left.size(); ++i) {
    WriteScan(
        (drive / "velodyne_points" / "data" / (Name(static_cast<int>(i), 10) + ".bin")).string(),
        FlatGroundScan());
  }
  return drive.string();
}

std::string WriteKittiTracking(const TempDir& dir, const KittiTestRig& rig,
                               const std::vector<cv::Mat>& left,
                               const std::vector<cv::Mat>& right) {
  const fs::path training = dir.path() / "training";
  WriteFrames(training / "image_02" / "0000", training / "image_03" / "0000", 6, left, right);
  WriteText(training / "calib" / "0000.txt", rig.Tracking());
  std::ostringstream labels;
  for (size_t i = 0; i < left.size(); ++i) {
    // The car of OneCarTracklet: location (camera 0) = (-ty, -tz, tx) = (0, 1.73, 10).
    labels << i << " 1 Car 0 0 -1.57 88.25 51.9166 113.25 71.625 1.5 2 4 0 1.73 10 -1.57\n"
           << i << " -1 DontCare -1 -1 -10 0 0 10 10 -1 -1 -1 -1000 -1000 -1000 -10\n";
    WriteScan((training / "velodyne" / "0000" / (Name(static_cast<int>(i), 6) + ".bin")).string(),
              FlatGroundScan());
  }
  WriteText(training / "label_02" / "0000.txt", labels.str());
  return (training / "image_02" / "0000").string();
}

}  // namespace attend::testing
