// attend.Tracker (python/bindings.h).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "python/arrays.h"
#include "python/bindings.h"
#include "python/in_use.h"
#include "tracker/target_tracker.h"
#include "util/error.h"

namespace attend::python {

namespace {

// attend.Tracker: a tracker of the configuration's kind on numpy frames.
class Tracker {
 public:
  explicit Tracker(const AttendOptions& options)
      : tracker_(TargetTracker::Create(options.attention.tracker)) {}

  int Start(const py::array& frame, const std::vector<int>& box) {
    const InUse::Scope scope(&in_use_, "start()");
    if (box.size() != 4) throw ConfigError("box: must be [x, y, width, height]");
    const cv::Mat bgr = BgrImage(frame, "frame");
    const py::gil_scoped_release release;
    return tracker_->StartFromBox(bgr, cv::Rect(box[0], box[1], box[2], box[3]));
  }

  int StartMask(const py::array& frame, const py::array& mask) {
    const InUse::Scope scope(&in_use_, "start()");
    const cv::Mat bgr = BgrImage(frame, "frame");
    const cv::Mat m = ImageView(ContiguousImage(mask, "mask"), "mask").clone();
    if (m.channels() != 1 || m.size() != bgr.size()) {
      throw InputError("mask: must be uint8 H x W of the frame's size");
    }
    const py::gil_scoped_release release;
    return tracker_->StartFromMask(bgr, m);
  }

  py::list Track(const py::array& frame) {
    const InUse::Scope scope(&in_use_, "track()");
    const cv::Mat bgr = BgrImage(frame, "frame");
    std::vector<TrackResult> results;
    {
      const py::gil_scoped_release release;
      tracker_->Track(bgr, &results);
    }
    py::list list;
    for (const TrackResult& r : results) {
      py::dict target;
      target["id"] = r.id;
      target["state"] = TrackStateName(r.state);
      target["box"] = py::make_tuple(r.box.x, r.box.y, r.box.width, r.box.height);
      target["area"] = r.area;
      target["roi"] = py::make_tuple(r.roi.x, r.roi.y, r.roi.width, r.roi.height);
      list.append(target);
    }
    return list;
  }

  py::object Mask(int id) {
    const InUse::Scope scope(&in_use_, "mask()");
    return MatArray(tracker_->Mask(id));
  }
  void Remove(int id) {
    const InUse::Scope scope(&in_use_, "remove()");
    tracker_->Remove(id);
  }
  std::vector<int> ids() {
    const InUse::Scope scope(&in_use_, "ids");
    return tracker_->ids();
  }
  std::string kind() const { return TrackerKindName(tracker_->kind()); }

 private:
  std::unique_ptr<TargetTracker> tracker_;
  // start() and track() release the GIL while they change the tracker: one call at a time.
  InUse in_use_{"attend.Tracker",
                "use one Tracker a thread (trackers of their own run in parallel)"};
};

}  // namespace

void RegisterTracking(py::module_& m) {
  py::class_<Tracker>(m, "Tracker")
      .def(py::init([](const Configuration& c) { return std::make_unique<Tracker>(c.options); }))
      .def("start", &Tracker::Start)
      .def("start_mask", &Tracker::StartMask)
      .def("track", &Tracker::Track)
      .def("mask", &Tracker::Mask)
      .def("remove", &Tracker::Remove)
      .def_property_readonly("ids", &Tracker::ids)
      .def_property_readonly("kind", &Tracker::kind);
}

}  // namespace attend::python
