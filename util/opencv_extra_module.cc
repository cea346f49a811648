// The module of util/opencv_extra.h: OpenCV's imgcodecs, videoio, video, tracking, objdetect,
// saliency and dnn behind attend's small interfaces. Built as libattend_opencv_extra.so, which
// links OpenCV and nothing of attend's libraries; compiled into the Python module too.
#include <opencv2/dnn.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/objdetect.hpp>
#include <opencv2/saliency.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videoio.hpp>
#include <opencv2/videoio/registry.hpp>

#include "util/opencv_extra.h"

namespace attend::cvextra {

namespace {

class CaptureImpl final : public Capture {
 public:
  bool IsOpened() const override { return capture_.isOpened(); }
  bool Grab() override { return capture_.grab(); }
  bool Read(cv::Mat* image) override { return capture_.read(*image); }
  bool Retrieve(cv::Mat* image) override { return capture_.retrieve(*image); }
  double Get(int property) const override { return capture_.get(property); }
  bool Set(int property, double value) override { return capture_.set(property, value); }
  cv::VideoCapture& capture() { return capture_; }

 private:
  cv::VideoCapture capture_;
};

class WriterImpl final : public Writer {
 public:
  WriterImpl(const std::string& path, int fourcc, double fps, cv::Size size)
      : writer_(path, fourcc, fps, size) {}
  bool IsOpened() const override { return writer_.isOpened(); }
  void Write(const cv::Mat& image) override { writer_.write(image); }

 private:
  cv::VideoWriter writer_;
};

class TrackerImpl final : public Tracker {
 public:
  explicit TrackerImpl(cv::Ptr<cv::Tracker> tracker) : tracker_(std::move(tracker)) {}
  void Init(const cv::Mat& image, const cv::Rect& box) override { tracker_->init(image, box); }
  bool Update(const cv::Mat& image, cv::Rect* box) override {
    return tracker_->update(image, *box);
  }

 private:
  cv::Ptr<cv::Tracker> tracker_;
};

class DenseFlowImpl final : public DenseFlow {
 public:
  explicit DenseFlowImpl(int preset) : flow_(cv::DISOpticalFlow::create(preset)) {}
  void Calc(const cv::Mat& from, const cv::Mat& to, cv::Mat* flow) override {
    flow_->calc(from, to, *flow);
  }

 private:
  cv::Ptr<cv::DISOpticalFlow> flow_;
};

class HogDetectorImpl final : public HogDetector {
 public:
  explicit HogDetectorImpl(bool daimler) {
    if (daimler) {
      hog_ =
          cv::HOGDescriptor(cv::Size(48, 96), cv::Size(16, 16), cv::Size(8, 8), cv::Size(8, 8), 9);
      hog_.setSVMDetector(cv::HOGDescriptor::getDaimlerPeopleDetector());
    } else {
      hog_.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
    }
  }
  cv::Size WindowSize() const override { return hog_.winSize; }
  void Detect(const cv::Mat& image, int levels, double hit_threshold, cv::Size stride,
              double scale, double group_threshold, std::vector<cv::Rect>* windows,
              std::vector<double>* weights) override {
    hog_.nlevels = levels;
    hog_.detectMultiScale(image, *windows, *weights, hit_threshold, stride, cv::Size(), scale,
                          group_threshold, false);
  }

 private:
  cv::HOGDescriptor hog_;
};

class CascadeImpl final : public Cascade {
 public:
  bool Load(const std::string& path) { return cascade_.load(path); }
  bool Empty() const override { return cascade_.empty(); }
  cv::Size OriginalWindowSize() const override {
    return const_cast<cv::CascadeClassifier&>(cascade_).getOriginalWindowSize();
  }
  void Detect(const cv::Mat& grey, double scale, int min_neighbours, cv::Size min_size,
              cv::Size max_size, std::vector<cv::Rect>* boxes, std::vector<int>* levels,
              std::vector<double>* weights) override {
    cascade_.detectMultiScale(grey, *boxes, *levels, *weights, scale, min_neighbours, 0, min_size,
                              max_size, true);
  }

 private:
  cv::CascadeClassifier cascade_;
};

class DnnNetImpl final : public DnnNet {
 public:
  explicit DnnNetImpl(cv::dnn::Net net) : net_(std::move(net)) {
    net_.setPreferableBackend(cv::dnn::DNN_BACKEND_OPENCV);
    net_.setPreferableTarget(cv::dnn::DNN_TARGET_CPU);
    names_ = net_.getUnconnectedOutLayersNames();
  }
  void Forward(const cv::Mat& image, double scale, const cv::Scalar& mean, bool swap_rb,
               std::vector<cv::Mat>* outputs) override {
    cv::dnn::blobFromImage(image, blob_, scale, image.size(), mean, swap_rb, false);
    net_.setInput(blob_);
    net_.forward(*outputs, names_);
  }
  const std::vector<std::string>& OutputNames() const override { return names_; }

 private:
  cv::dnn::Net net_;
  std::vector<std::string> names_;
  cv::Mat blob_;
};

class ModuleImpl final : public Module {
 public:
  cv::Mat Decode(const std::vector<uchar>& bytes, int flags) override {
    return cv::imdecode(bytes, flags);
  }
  cv::Mat Read(const std::string& path, int flags) override { return cv::imread(path, flags); }
  bool Write(const std::string& path, const cv::Mat& image,
             const std::vector<int>& params) override {
    return cv::imwrite(path, image, params);
  }
  bool Encode(const std::string& extension, const cv::Mat& image, const std::vector<int>& params,
              std::vector<uchar>* bytes) override {
    return cv::imencode(extension, image, *bytes, params);
  }
  std::unique_ptr<Capture> OpenCapture(const std::string& source, int api) override {
    auto capture = std::make_unique<CaptureImpl>();
    capture->capture().open(source, api);
    return capture;
  }
  std::unique_ptr<Capture> OpenCamera(int index, int api) override {
    auto capture = std::make_unique<CaptureImpl>();
    capture->capture().open(index, api);
    return capture;
  }
  bool HasBackend(int api) override {
    return cv::videoio_registry::hasBackend(static_cast<cv::VideoCaptureAPIs>(api));
  }
  std::unique_ptr<Writer> OpenWriter(const std::string& path, int fourcc, double fps,
                                     cv::Size size) override {
    return std::make_unique<WriterImpl>(path, fourcc, fps, size);
  }
  std::unique_ptr<Tracker> CreateTracker(TrackerType type, double kcf_detect_thresh) override {
    if (type == TrackerType::kKcf) {
      cv::TrackerKCF::Params params;
      params.detect_thresh = static_cast<float>(kcf_detect_thresh);
      return std::make_unique<TrackerImpl>(cv::TrackerKCF::create(params));
    }
    return std::make_unique<TrackerImpl>(cv::TrackerCSRT::create());
  }
  std::unique_ptr<DenseFlow> CreateDisFlow(int preset) override {
    return std::make_unique<DenseFlowImpl>(preset);
  }
  std::unique_ptr<HogDetector> CreateHog(bool daimler) override {
    return std::make_unique<HogDetectorImpl>(daimler);
  }
  std::unique_ptr<Cascade> LoadCascade(const std::string& path) override {
    auto cascade = std::make_unique<CascadeImpl>();
    cascade->Load(path);
    return cascade;
  }
  std::unique_ptr<DnnNet> ReadNet(const std::string& model, const std::string& config) override {
    return std::make_unique<DnnNetImpl>(cv::dnn::readNet(model, config));
  }
  bool ComputeStaticSaliency(StaticSaliencyType type, const cv::Mat& bgr,
                             cv::Mat* map) override {
    cv::Ptr<cv::saliency::StaticSaliency> detector;
    if (type == StaticSaliencyType::kSpectralResidual) {
      detector = cv::saliency::StaticSaliencySpectralResidual::create();
    } else {
      detector = cv::saliency::StaticSaliencyFineGrained::create();
    }
    return detector->computeSaliency(bgr, *map);
  }
};

}  // namespace

}  // namespace attend::cvextra

// The entry point (util/opencv_extra.h); visible from the shared library.
extern "C" __attribute__((visibility("default"))) attend::cvextra::Module* attend_opencv_extra(
    int abi_version) {
  if (abi_version != attend::cvextra::kAbiVersion) return nullptr;
  static attend::cvextra::ModuleImpl module;
  return &module;
}
