// KITTI raw drives' 3D labels, tracklet_labels.xml (the devkit's raw data readme): one tracklet
// per object, its size and its pose in every frame it is labelled in, in Velodyne coordinates.
// The file is boost::serialization's XML; it is read here by a small strict reader of the
// subset KITTI writes (a declaration, a DOCTYPE, elements with attributes and text, no
// entities, no CDATA), so that no XML library is needed.
#pragma once

#include <string>
#include <vector>

namespace attend {

// One frame of a tracklet: the box's bottom centre (tx, ty, tz) and rotation (rz, yaw about the
// Velodyne's up axis; rx, ry are 0 in KITTI's labels) in Velodyne coordinates, metres and
// radians; the label's state (0 unset, 1 interpolated, 2 labelled), occlusion (0 fully visible,
// 1 partly, 2 largely occluded, -1/3 unknown) and truncation (0 in the image, 1 truncated,
// 2 out of the image, 99 ignored).
struct KittiTrackletPose {
  double tx = 0.0, ty = 0.0, tz = 0.0;
  double rx = 0.0, ry = 0.0, rz = 0.0;
  int state = 0;
  int occlusion = 0;
  int truncation = 0;
};

struct KittiTracklet {
  std::string type;  // objectType: Car, Van, Truck, Pedestrian, Person (sitting), Cyclist, ...
  double h = 0.0, w = 0.0, l = 0.0;  // height, width, length, metres
  int first_frame = 0;               // the frame of poses[0]; poses[i] is frame first_frame + i
  std::vector<KittiTrackletPose> poses;
};

// Reads tracklet_labels.xml. InputError naming the file and line of malformed XML, a missing
// or non-numeric field, or a <count> that is not the number of items that follow it.
std::vector<KittiTracklet> ReadKittiTracklets(const std::string& path);

// The element tree of an XML text in the subset above (for the reader and its tests).
struct XmlElement {
  std::string name;
  std::string text;  // the character data of an element without children, trimmed
  int line = 0;      // where its start tag is
  std::vector<XmlElement> children;
};
// The root element of `text`; InputError "WHAT line N: ..." for anything outside the subset.
XmlElement ParseXmlSubset(const std::string& text, const std::string& what);

}  // namespace attend
