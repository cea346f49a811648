// The dnn backend (features/dnn_detector.h, dnn_decoders.h): output tensors written by the test
// decode to the boxes they hold; a Darknet network and an ONNX network written by the test,
// whose outputs are known from their weights, load end to end and find the white square drawn
// for them; the model files' errors; the reference data's real networks when present.
#include "features/dnn_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "config/feature_list.h"
#include "config/param_block.h"
#include "features/builtin.h"
#include "features/detectors.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// A 1 x rows x cols float tensor.
cv::Mat Tensor(int rows, int cols) {
  const int sizes[] = {1, rows, cols};
  return cv::Mat(3, sizes, CV_32F, cv::Scalar(0));
}

float* Row(cv::Mat* tensor, int row) { return tensor->ptr<float>(0, row); }

TEST(DnnDecoders, YoloxRowsDecodeToTheirGridCellsBoxes) {
  const cv::Size input(64, 32);
  // Cells: 8x4 at stride 8, 4x2 at 16, 2x1 at 32: 42 rows of 5 + 2 classes.
  cv::Mat out = Tensor(42, 7);
  // Stride 8, cell (5, 2): row 2 * 8 + 5 = 21. Centre (5.5, 2.5) x 8, size 16 x 8.
  float* a = Row(&out, 21);
  a[0] = 0.5f, a[1] = 0.5f, a[2] = std::log(2.f), a[3] = 0.f, a[4] = 0.9f, a[5] = 0.8f,
  a[6] = 0.1f;
  // Stride 32, cell (1, 0): row 32 + 8 + 1 = 41, class 1.
  float* b = Row(&out, 41);
  b[0] = 0.f, b[1] = 0.f, b[2] = 0.f, b[3] = 0.f, b[4] = 0.7f, b[5] = 0.1f, b[6] = 0.9f;
  // Below the score: objectness 0.5 x class 0.5.
  float* c = Row(&out, 0);
  c[4] = 0.5f, c[5] = 0.5f;
  const DnnOutputs outputs{{"output"}, {out}};
  ASSERT_EQ(CheckDnnOutputs(DnnDecoder::kYolox, outputs, input, 1), "");
  std::vector<DnnBox> boxes = DecodeDnnOutputs(DnnDecoder::kYolox, outputs, input, {0, 1}, 0.3f);
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0].class_index, 0);
  EXPECT_NEAR(boxes[0].score, 0.72f, 1e-5);
  EXPECT_NEAR(boxes[0].box.x, 44.f - 8.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.y, 20.f - 4.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.width, 16.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.height, 8.f, 1e-4);
  EXPECT_EQ(boxes[1].class_index, 1);
  EXPECT_NEAR(boxes[1].box.x, 32.f - 16.f, 1e-4);
  EXPECT_NEAR(boxes[1].box.width, 32.f, 1e-4);
  // Only class 0 asked for: the second row's best class among them is below the score.
  boxes = DecodeDnnOutputs(DnnDecoder::kYolox, outputs, input, {0}, 0.3f);
  EXPECT_EQ(boxes.size(), 1u);
}

TEST(DnnDecoders, DarknetRowsAreRelativeToTheInput) {
  cv::Mat rows(2, 7, CV_32F, cv::Scalar(0));
  const float first[] = {0.5f, 0.25f, 0.25f, 0.5f, 0.9f, 0.85f, 0.0f};
  const float second[] = {0.1f, 0.1f, 0.1f, 0.1f, 0.2f, 0.1f, 0.1f};
  std::copy(first, first + 7, rows.ptr<float>(0));
  std::copy(second, second + 7, rows.ptr<float>(1));
  const DnnOutputs outputs{{"yolo_1"}, {rows}};
  const cv::Size input(128, 64);
  ASSERT_EQ(CheckDnnOutputs(DnnDecoder::kDarknet, outputs, input, 1), "");
  const std::vector<DnnBox> boxes =
      DecodeDnnOutputs(DnnDecoder::kDarknet, outputs, input, {0}, 0.3f);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].box.x, 64.f - 16.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.y, 16.f - 16.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.width, 32.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.height, 32.f, 1e-4);
  EXPECT_NEAR(boxes[0].score, 0.85f, 1e-6);
}

TEST(DnnDecoders, YunetScoresAreTheGeometricMeanOfClassAndObjectness) {
  const cv::Size input(32, 32);
  DnnOutputs outputs;
  for (const int stride : kDnnStrides) {
    const int cells = (32 / stride) * (32 / stride);
    for (const auto& [head, cols] :
         {std::pair<const char*, int>{"cls", 1}, {"obj", 1}, {"bbox", 4}}) {
      outputs.names.push_back(std::string(head) + "_" + std::to_string(stride));
      outputs.values.push_back(Tensor(cells, cols));
    }
  }
  ASSERT_EQ(CheckDnnOutputs(DnnDecoder::kYunet, outputs, input, 0), "");
  // Stride 16, cell (1, 1) = row 3: cls 0.81, obj 1.2 (clamped to 1): score 0.9.
  outputs.values[3].ptr<float>(0, 3)[0] = 0.81f;
  outputs.values[4].ptr<float>(0, 3)[0] = 1.2f;
  float* box = outputs.values[5].ptr<float>(0, 3);
  box[0] = 0.25f, box[1] = 0.5f, box[2] = 0.f, box[3] = std::log(1.5f);
  const std::vector<DnnBox> boxes = DecodeDnnOutputs(DnnDecoder::kYunet, outputs, input, {}, 0.5f);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NEAR(boxes[0].score, 0.9f, 1e-5);
  EXPECT_NEAR(boxes[0].box.x, 20.f - 8.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.y, 24.f - 12.f, 1e-4);
  EXPECT_NEAR(boxes[0].box.height, 24.f, 1e-4);
}

TEST(DnnDecoders, OutputsOfAnotherLayoutAreNamedWithTheirShapes) {
  const DnnOutputs wrong{{"output"}, {Tensor(10, 85)}};
  const std::string message = CheckDnnOutputs(DnnDecoder::kYolox, wrong, cv::Size(64, 32), 0);
  EXPECT_NE(message.find("1x42x"), std::string::npos) << message;
  EXPECT_NE(message.find("output 1x10x85"), std::string::npos) << message;
  EXPECT_NE(CheckDnnOutputs(DnnDecoder::kYunet, wrong, cv::Size(64, 32), 0).find("cls_S"),
            std::string::npos);
  const DnnOutputs narrow{{"yolo"}, {cv::Mat(3, 5, CV_32F, cv::Scalar(0))}};
  EXPECT_NE(CheckDnnOutputs(DnnDecoder::kDarknet, narrow, cv::Size(32, 32), 0), "");
  // Class 3 asked of a network with two.
  const DnnOutputs two{{"yolo"}, {cv::Mat(3, 7, CV_32F, cv::Scalar(0))}};
  EXPECT_NE(CheckDnnOutputs(DnnDecoder::kDarknet, two, cv::Size(32, 32), 3), "");
}

// A Darknet network of one 1x1 convolution and a [yolo] layer of one anchor (16 x 16 px, one
// class) on a 32 x 32 input: the objectness is 20 x (the pixel's R + G + B in [0, 1]) - 10, so
// only white pixels hold an object, centred on their cell, of the anchor's size.
void WriteDarknet(const fs::path& cfg, const fs::path& weights) {
  std::ofstream(cfg) << "[net]\nwidth=32\nheight=32\nchannels=3\n\n"
                        "[convolutional]\nsize=1\nstride=1\npad=0\nfilters=6\nactivation=linear\n\n"
                        "[yolo]\nmask=0\nanchors=16,16\nclasses=1\nnum=1\n";
  std::ofstream out(weights, std::ios::binary);
  const int32_t header[] = {0, 2, 0};
  const uint64_t seen = 0;
  out.write(reinterpret_cast<const char*>(header), sizeof(header));
  out.write(reinterpret_cast<const char*>(&seen), sizeof(seen));
  // Biases: tx ty tw th objectness class.
  const float biases[6] = {0.f, 0.f, 0.f, 0.f, -10.f, 10.f};
  out.write(reinterpret_cast<const char*>(biases), sizeof(biases));
  float kernel[6][3] = {};
  for (float& weight : kernel[4]) weight = 20.f / 3.f;
  out.write(reinterpret_cast<const char*>(kernel), sizeof(kernel));
}

// A frame of black with one white pixel at `at`.
cv::Mat Dot(cv::Size size, cv::Point at) {
  cv::Mat image(size, CV_8UC3, cv::Scalar::all(0));
  image.at<cv::Vec3b>(at) = cv::Vec3b(255, 255, 255);
  return image;
}

std::unique_ptr<DnnDetector> LoadDetector(const std::string& yaml, const std::string& label) {
  const ParamBlock params = ParamBlock::Parse(yaml, "test.yaml");
  DnnDetectorOptions options = DnnDetectorOptions::ForDecoder(DnnDecoder::kDarknet);
  options.model = params.GetString("model", "");
  options.config = params.GetString("config", "");
  const std::string decoder = params.GetString("decoder", "darknet");
  options.decoder = decoder == "yolox"   ? DnnDecoder::kYolox
                    : decoder == "yunet" ? DnnDecoder::kYunet
                                         : DnnDecoder::kDarknet;
  options.input_size = params.GetInt("input_size", options.input_size);
  return DnnDetector::Load(options, params, FeatureSetup(), label);
}

TEST(DnnDetector, ATinyDarknetNetworkFindsTheWhiteDotWhereItsWeightsSay) {
  testing::TempDir dir;
  const fs::path cfg = dir.path() / "tiny.cfg", weights = dir.path() / "tiny.weights";
  WriteDarknet(cfg, weights);
  std::unique_ptr<DnnDetector> detector = LoadDetector(
      "{model: " + weights.string() + ", config: " + cfg.string() + "}", "person");
  // A 60 x 30 image is padded to 64 x 32: the dot's cell is (40, 10), its box 16 x 16 there.
  std::vector<Detection> found;
  cv::Size padded;
  detector->Detect(Dot(cv::Size(60, 30), cv::Point(40, 10)), &found, &padded);
  EXPECT_EQ(padded, cv::Size(64, 32));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].label, "person");
  EXPECT_GT(found[0].confidence, 0.99f);
  EXPECT_NEAR(found[0].box.x + 0.5 * found[0].box.width, 40.5, 1.0);
  EXPECT_NEAR(found[0].box.y + 0.5 * found[0].box.height, 10.5, 1.0);
  EXPECT_NEAR(found[0].box.width, 16, 1);
  EXPECT_NEAR(found[0].box.height, 16, 1);
  // Nothing white, nothing found.
  detector->Detect(cv::Mat(30, 60, CV_8UC3, cv::Scalar::all(0)), &found);
  EXPECT_TRUE(found.empty());
}

TEST(DnnDetector, TwoDotsCloserThanTheNmsOverlapAreOneBox) {
  testing::TempDir dir;
  const fs::path cfg = dir.path() / "tiny.cfg", weights = dir.path() / "tiny.weights";
  WriteDarknet(cfg, weights);
  std::unique_ptr<DnnDetector> detector = LoadDetector(
      "{model: " + weights.string() + ", config: " + cfg.string() + "}", "person");
  cv::Mat image = Dot(cv::Size(64, 32), cv::Point(20, 10));
  image.at<cv::Vec3b>(cv::Point(21, 10)) = cv::Vec3b(255, 255, 255);  // IoU 15/17 with the first
  image.at<cv::Vec3b>(cv::Point(50, 20)) = cv::Vec3b(255, 255, 255);  // apart
  std::vector<Detection> found;
  detector->Detect(image, &found);
  EXPECT_EQ(found.size(), 2u);
}

TEST(DnnDetector, AMissingModelIsAConfigErrorNamingKeyPathAndTheModelsPage) {
  const std::string message = testing::ConfigErrorOf(
      [] { LoadDetector("{model: no/such/net.onnx, decoder: yolox}", "person"); });
  EXPECT_NE(message.find("model"), std::string::npos) << message;
  EXPECT_NE(message.find("no/such/net.onnx"), std::string::npos) << message;
  EXPECT_NE(message.find("docs/MODELS.md"), std::string::npos) << message;
  EXPECT_NE(message.find("ATTEND_MODELS"), std::string::npos) << message;
}

// The status and message of what `load` throws.
std::pair<ExitStatus, std::string> ErrorOf(const std::function<void()>& load) {
  try {
    load();
  } catch (const Error& e) {
    return {e.status(), e.what()};
  }
  return {ExitStatus::kOk, ""};
}

TEST(DnnDetector, AFileCvDnnCannotReadIsBadInputWithItsMessage) {
  testing::TempDir dir;
  const std::string file = dir.Write("broken.onnx", "this is not a network\n");
  const auto [status, message] =
      ErrorOf([&] { LoadDetector("{model: " + file + ", decoder: yolox}", "person"); });
  EXPECT_EQ(status, ExitStatus::kBadInput) << message;
  EXPECT_NE(message.find(file), std::string::npos) << message;
  EXPECT_NE(message.find("cv::dnn"), std::string::npos) << message;
}

TEST(DnnDetector, ANetworkWhoseOutputsDoNotFitTheDecoderIsBadInputNamingTheShapes) {
  testing::TempDir dir;
  const fs::path cfg = dir.path() / "tiny.cfg", weights = dir.path() / "tiny.weights";
  WriteDarknet(cfg, weights);
  const auto [status, message] = ErrorOf([&] {
    LoadDetector("{model: " + weights.string() + ", config: " + cfg.string() +
                     ", decoder: yolox}",
                 "person");
  });
  EXPECT_EQ(status, ExitStatus::kBadInput) << message;
  EXPECT_NE(message.find("decoder yolox"), std::string::npos) << message;
  EXPECT_NE(message.find("the network gives"), std::string::npos) << message;
}

// Debian's Python (a python3 earlier on the PATH, as pyenv's, may lack Debian's packages).
std::string Python() { return fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3"; }

// Whether Python's onnx package is there (Debian's python3-onnx).
bool HaveOnnx() {
  return std::system((Python() + " -c 'import onnx, numpy' > /dev/null 2>&1").c_str()) == 0;
}

TEST(DnnDetector, AnOnnxNetworkBuiltByTheTestLoadsThroughThePeopleChannel) {
  if (!HaveOnnx()) GTEST_SKIP() << "python3's onnx is absent (Debian's python3-onnx)";
  testing::TempDir dir;
  const fs::path model = dir.path() / "yolox_like.onnx";
  const std::string script = testing::ProjectRoot() + "/tests/features/make_yolox_onnx.py";
  ASSERT_EQ(std::system((Python() + " " + script + " " + model.string()).c_str()), 0);
  // The channel on the whole frame at its own scale: input_size 64 for a 64 x 32 frame.
  const std::vector<FeatureSpec> specs = ReadFeatureList(
      ParamBlock::Parse("features: [{name: people, backend: dnn, gate: frame, min_height: 4, "
                        "input_size: 64, model: " +
                            model.string() + "}]",
                        "test.yaml"),
      "features");
  std::unique_ptr<FeatureMap> people = BuiltinFeatures().Create(specs.at(0), FeatureSetup());
  // The network's stride-8 head finds an 8 x 8 white block at cell (5, 2) as a 16 x 16 box
  // centred on the cell's centre (make_yolox_onnx.py).
  cv::Mat frame(32, 64, CV_8UC3, cv::Scalar::all(0));
  frame(cv::Rect(40, 16, 8, 8)).setTo(cv::Scalar::all(255));
  ObjectChannelOptions options;
  options.gate = DetectorGate::kFrame;
  options.min_height = 4;
  std::vector<Detection> found;
  {
    // The same network through the channel, as the feature runs it.
    const ParamBlock params = ParamBlock::Parse("{model: " + model.string() + "}", "test.yaml");
    DnnDetectorOptions dnn;
    dnn.model = model.string();
    dnn.input_size = 64;
    std::shared_ptr<DnnDetector> detector = DnnDetector::Load(dnn, params, FeatureSetup(), "person");
    ObjectChannel channel(options, {cv::Size(32, 64), 64.0, 64, 1.0}, "person",
                          [detector](const cv::Mat& image, double, std::vector<Detection>* out) {
                            detector->Detect(image, out);
                          });
    cv::Mat map;
    channel.Compute(frame, {}, &map);
    found = channel.detections();
    EXPECT_EQ(channel.last_searched_pixels(), 64.0 * 32.0);
    EXPECT_GT(map.at<float>(20, 44), 0.5f);
    EXPECT_EQ(map.at<float>(2, 2), 0.f);
  }
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].box, cv::Rect(36, 12, 16, 16));
  EXPECT_NEAR(found[0].confidence, 1.0, 0.01);
  EXPECT_NE(people, nullptr);
}

// The image at `path` with its longer side scaled to `side` px, as the channel gives it to a
// network on the whole frame; empty when it cannot be read.
cv::Mat ReadScaled(const std::string& path, double side) {
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  if (image.empty()) return image;
  cv::Mat scaled;
  const double scale = side / std::max(image.cols, image.rows);
  cv::resize(image, scaled, cv::Size(), scale, scale, cv::INTER_AREA);
  return scaled;
}

// The reference data's networks: each loads, and YOLOX finds people in a real frame.
TEST(DnnDetector, TheReferenceNetworksLoadAndYoloxFindsPeopleInARealFrame) {
  const std::string models = testing::SharedData() + "/models";
  const std::string frame_path = testing::SharedData() + "/mot/TUD-Stadtmitte/left";
  if (!fs::exists(models + "/yolox/yolox_nano.onnx") || !fs::exists(frame_path)) {
    GTEST_SKIP() << "no " << models << " or " << frame_path << " (the reference data)";
  }
  const std::string body = models + "/yolo_fastest/yolo-fastest-1.1_body";
  EXPECT_NO_THROW(LoadDetector("{model: " + body + ".weights, config: " + body + ".cfg}", ""));
  std::unique_ptr<DnnDetector> yolox =
      LoadDetector("{model: " + models + "/yolox/yolox_nano.onnx, decoder: yolox}", "person");
  std::vector<fs::path> frames;
  for (const auto& entry : fs::directory_iterator(frame_path)) frames.push_back(entry.path());
  std::sort(frames.begin(), frames.end());
  ASSERT_FALSE(frames.empty());
  const cv::Mat scaled = ReadScaled(frames.front().string(), 416.0);
  ASSERT_FALSE(scaled.empty());
  std::vector<Detection> found;
  yolox->Detect(scaled, &found);
  // TUD-Stadtmitte's first frame has several pedestrians in full view.
  EXPECT_GE(found.size(), 3u);
  for (const Detection& detection : found) EXPECT_GT(detection.box.height, detection.box.width);
}

// YuNet finds faces in a real crowd photograph (the reference data's crowd200).
TEST(DnnDetector, YunetFindsFacesInARealCrowdPhotograph) {
  const std::string model = testing::SharedData() + "/models/yunet/yunet_n_640_640.onnx";
  const std::string photo = testing::SharedData() + "/fixations/crowd200/stimuli/001.jpg";
  if (!fs::exists(model) || !fs::exists(photo)) {
    GTEST_SKIP() << "no " << model << " or " << photo << " (the reference data)";
  }
  std::unique_ptr<DnnDetector> yunet =
      LoadDetector("{model: " + model + ", decoder: yunet, input_size: 640}", "face");
  const cv::Mat scaled = ReadScaled(photo, 640.0);
  ASSERT_FALSE(scaled.empty());
  std::vector<Detection> faces;
  yunet->Detect(scaled, &faces);
  ASSERT_GE(faces.size(), 2u);
  for (const Detection& face : faces) {
    EXPECT_EQ(face.label, "face");
    // A face's box is about as tall as it is wide.
    const double aspect = static_cast<double>(face.box.height) / face.box.width;
    EXPECT_GT(aspect, 0.8) << face.box;
    EXPECT_LT(aspect, 2.0) << face.box;
  }
}

}  // namespace
}  // namespace attend
