// attend calibrate: a stereo camera's calibration from chessboard pairs, or the conversion of
// a rectified pair's projection matrices (docs/STEREO3D.md, "Calibration").
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "app/calibrate_stereo.h"
#include "app/convert_projections.h"
#include "cli/commands.h"
#include "util/error.h"

namespace attend {

namespace {

struct CalibrateArguments {
  std::string left, right, board, out, from_kitti, from_euroc, size;
  double square = 0.0;
  double alpha = 0.0;
};

cv::Size ParseImageSize(const std::string& text) {
  if (text.empty()) return {};
  static const std::regex pattern("([0-9]{1,5})[xX]([0-9]{1,5})");
  std::smatch match;
  if (!std::regex_match(text, match, pattern) || std::stoi(match[1]) < 1 ||
      std::stoi(match[2]) < 1) {
    throw ConfigError("--size must be WIDTHxHEIGHT in pixels (1242x375), got '" + text + "'");
  }
  return {std::stoi(match[1]), std::stoi(match[2])};
}

// --from-kitti, --from-euroc: the rectified form written, and a line of JSON.
int Convert(const CalibrateArguments& args) {
  if (!args.left.empty() || !args.right.empty() || !args.board.empty() || args.square != 0.0) {
    throw ConfigError("--from-kitti and --from-euroc convert a file: --left, --right, --board "
                      "and --square calibrate from chessboard pairs instead");
  }
  if (!args.size.empty() && !args.from_euroc.empty()) {
    throw ConfigError("--size is for --from-kitti (EuRoC's calib.txt has width and height)");
  }
  StereoCalibration calibration = !args.from_kitti.empty()
                                      ? ReadKittiProjections(args.from_kitti,
                                                             ParseImageSize(args.size))
                                      : ReadEurocProjections(args.from_euroc);
  WriteStereoCalibration(calibration, args.out);
  calibration = ReadStereoCalibration(args.out);
  const nlohmann::ordered_json json = {
      {"out", args.out},
      {"form", "rectified"},
      {"from", !args.from_kitti.empty() ? args.from_kitti : args.from_euroc},
      {"image_size", {calibration.image_size.width, calibration.image_size.height}},
      {"focal_px", calibration.focal_px()},
      {"cx", calibration.cx()},
      {"cy", calibration.cy()},
      {"baseline_m", calibration.baseline_m()}};
  std::cout << json.dump(2) << std::endl;
  return 0;
}

int Calibrate(const CalibrateArguments& args) {
  if (!args.from_kitti.empty() || !args.from_euroc.empty()) return Convert(args);
  for (const auto& [flag, value] : {std::pair<const char*, const std::string*>{"--left", &args.left},
                                    {"--right", &args.right},
                                    {"--board", &args.board}}) {
    if (value->empty()) {
      throw ConfigError(std::string(flag) + " is required (or --from-kitti / --from-euroc)");
    }
  }
  if (!args.size.empty()) throw ConfigError("--size is for --from-kitti");
  CalibrateRequest request;
  request.left = args.left;
  request.right = args.right;
  request.board = ParseBoardSize(args.board);
  request.square_m = args.square;
  request.alpha = args.alpha;
  request.out = args.out;
  const CalibrateResult result = CalibrateStereo(request);
  std::cout << result.ToJson(args.out).dump(2) << std::endl;
  return 0;
}

}  // namespace

void AddCalibrateCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<CalibrateArguments>();
  CLI::App* command = app.add_subcommand(
      "calibrate",
      "Calibrate a stereo camera from chessboard pairs (OpenCV's findChessboardCorners, "
      "calibrateCamera, stereoCalibrate and stereoRectify) and write calib.yaml, which "
      "attend run reads as SEQ/calib.yaml or --calib FILE and rectifies raw pairs with; or "
      "convert the projection matrices of a rectified pair (KITTI, EuRoC) into calib.yaml. "
      "Prints one JSON object: the RMS reprojection error, the pairs used and skipped, and the "
      "rows of the pairs rectified (docs/STEREO3D.md).");
  command->add_option("--left", args->left, "Folder of the left views (sorted by name)")
      ->type_name("LDIR");
  command->add_option("--right", args->right,
                      "Folder of the right views, paired with the left ones by sorted name")
      ->type_name("RDIR");
  command->add_option("--board", args->board,
                      "The chessboard's INNER corners, columns x rows: 9x6 for a board of 10 x 7 "
                      "squares")
      ->type_name("COLSxROWS");
  command->add_option("--square", args->square,
                      "The side of one square, metres (sets the unit of the baseline)")
      ->type_name("METRES");
  command->add_option("--alpha", args->alpha,
                      "stereoRectify's free scaling in [0, 1]: 0 (default) keeps only pixels "
                      "valid in both views, 1 keeps every pixel (black borders)")
      ->type_name("A");
  command->add_option("--out", args->out, "The calibration to write (calib.yaml)")
      ->type_name("FILE")
      ->required();
  auto* kitti = command->add_option(
      "--from-kitti", args->from_kitti,
      "Convert KITTI's calib_cam_to_cam.txt (P_rect_02, P_rect_03, S_rect_02) or the odometry "
      "set's calib.txt (P2, P3; with --size) instead of calibrating");
  kitti->type_name("FILE");
  auto* euroc = command->add_option(
      "--from-euroc", args->from_euroc,
      "Convert an EuRoC calib.txt (P_left, P_right, width, height) instead of calibrating");
  euroc->type_name("FILE");
  kitti->excludes(euroc);
  command->add_option("--size", args->size,
                      "With --from-kitti: the frames' size, for a file without S_rect_02")
      ->type_name("WxH");
  command->callback([args, action] { *action = [args] { return Calibrate(*args); }; });
}

ATTEND_COMMAND(25, "calibrate", AddCalibrateCommand);

}  // namespace attend
