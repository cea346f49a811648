#include "io/kitti_tracklets.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "util/error.h"

namespace attend {

namespace {

// A recursive-descent reader over the text, counting lines for its messages.
class XmlReader {
 public:
  XmlReader(const std::string& text, const std::string& what) : text_(text), what_(what) {}

  XmlElement Document() {
    SkipMisc();
    if (!Peek("<")) Fail("expected the root element");
    XmlElement root = Element();
    SkipMisc();
    if (pos_ < text_.size()) Fail("text after the root element </" + root.name + ">");
    return root;
  }

 private:
  [[noreturn]] void Fail(const std::string& message) const {
    throw InputError(what_ + " line " + std::to_string(line_) + ": " + message);
  }

  bool Peek(const char* token) const { return text_.compare(pos_, std::strlen(token), token) == 0; }

  void Advance(size_t count) {
    for (size_t i = 0; i < count && pos_ < text_.size(); ++i) {
      if (text_[pos_++] == '\n') ++line_;
    }
  }

  void SkipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) Advance(1);
  }

  // Past `end`, which must come.
  void SkipPast(const char* end, const char* what) {
    const size_t at = text_.find(end, pos_);
    if (at == std::string::npos) Fail(std::string("unterminated ") + what);
    Advance(at + std::strlen(end) - pos_);
  }

  // Whitespace, the declaration, a DOCTYPE and comments, outside and between elements.
  void SkipMisc() {
    for (;;) {
      SkipSpace();
      if (Peek("<?")) {
        SkipPast("?>", "declaration");
      } else if (Peek("<!--")) {
        SkipPast("-->", "comment");
      } else if (Peek("<!DOCTYPE")) {
        SkipPast(">", "DOCTYPE");
      } else {
        return;
      }
    }
  }

  std::string Name() {
    const size_t start = pos_;
    while (pos_ < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '_' ||
            text_[pos_] == '-' || text_[pos_] == '.' || text_[pos_] == ':')) {
      ++pos_;
    }
    if (pos_ == start) Fail("expected a name");
    return text_.substr(start, pos_ - start);
  }

  // The attributes of a start tag (KITTI's class_id, version ...): read and dropped.
  void SkipAttributes() {
    for (;;) {
      SkipSpace();
      if (Peek("/>") || Peek(">")) return;
      Name();
      SkipSpace();
      if (!Peek("=")) Fail("expected '=' after an attribute name");
      Advance(1);
      SkipSpace();
      if (!Peek("\"") && !Peek("'")) Fail("expected a quoted attribute value");
      const char quote = text_[pos_];
      Advance(1);
      const size_t end = text_.find(quote, pos_);
      if (end == std::string::npos) Fail("unterminated attribute value");
      Advance(end + 1 - pos_);
    }
  }

  // One element, its start tag at pos_. Children and text do not mix (KITTI never does).
  XmlElement Element(int depth = 0) {
    // KITTI nests 5 deep; a bound keeps a hostile file from exhausting the stack.
    if (depth > kMaxDepth) Fail("elements nest deeper than " + std::to_string(kMaxDepth));
    XmlElement element;
    element.line = line_;
    Advance(1);  // '<'
    element.name = Name();
    SkipAttributes();
    if (Peek("/>")) {
      Advance(2);
      return element;
    }
    Advance(1);  // '>'
    std::string text;
    for (;;) {
      if (pos_ >= text_.size()) Fail("<" + element.name + "> is not closed");
      if (Peek("</")) break;
      if (Peek("<!--")) {
        SkipPast("-->", "comment");
      } else if (Peek("<![CDATA[") || Peek("<!") || Peek("<?")) {
        Fail("CDATA and declarations inside elements are not read");
      } else if (Peek("<")) {
        element.children.push_back(Element(depth + 1));
      } else {
        if (text_[pos_] == '&') Fail("character entities ('&...;') are not read");
        text += text_[pos_];
        Advance(1);
      }
    }
    const int close_line = line_;
    Advance(2);
    const std::string close = Name();
    SkipSpace();
    if (!Peek(">")) Fail("expected '>' after </" + close);
    Advance(1);
    if (close != element.name) {
      line_ = close_line;
      Fail("</" + close + "> closes <" + element.name + "> of line " +
           std::to_string(element.line));
    }
    const size_t first = text.find_first_not_of(" \t\r\n");
    element.text = first == std::string::npos
                       ? ""
                       : text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
    if (!element.children.empty() && !element.text.empty()) {
      line_ = element.line;
      Fail("<" + element.name + "> mixes text and elements");
    }
    return element;
  }

  static constexpr int kMaxDepth = 32;
  const std::string& text_;
  std::string what_;
  size_t pos_ = 0;
  int line_ = 1;
};

// The fields of the tracklets, with the file named in every error.
class TrackletFields {
 public:
  explicit TrackletFields(const std::string& path) : path_(path) {}

  [[noreturn]] void Fail(const XmlElement& at, const std::string& message) const {
    throw InputError(path_ + " line " + std::to_string(at.line) + ": " + message);
  }

  const XmlElement& Child(const XmlElement& parent, const std::string& name) const {
    for (const XmlElement& child : parent.children) {
      if (child.name == name) return child;
    }
    Fail(parent, "<" + parent.name + "> has no <" + name + ">");
  }

  double Number(const XmlElement& parent, const std::string& name) const {
    const XmlElement& field = Child(parent, name);
    char* end = nullptr;
    const double value = std::strtod(field.text.c_str(), &end);
    if (field.text.empty() || *end != '\0' || !std::isfinite(value)) {
      Fail(field, "<" + name + "> holds '" + field.text + "', not a number");
    }
    return value;
  }

  int Integer(const XmlElement& parent, const std::string& name) const {
    const double value = Number(parent, name);
    // In int's range first: a cast of anything else is undefined.
    if (std::abs(value) >= 1e9 || value != std::floor(value)) {
      Fail(Child(parent, name), "<" + name + "> must be a whole number");
    }
    return static_cast<int>(value);
  }

  // The <item> children of `list`, which must be as many as its <count> says.
  std::vector<const XmlElement*> Items(const XmlElement& list) const {
    std::vector<const XmlElement*> items;
    for (const XmlElement& child : list.children) {
      if (child.name == "item") items.push_back(&child);
    }
    const int count = Integer(list, "count");
    if (count != static_cast<int>(items.size())) {
      Fail(list, "<" + list.name + "> has count " + std::to_string(count) + " but " +
                     std::to_string(items.size()) + " items");
    }
    return items;
  }

  KittiTrackletPose Pose(const XmlElement& item) const {
    KittiTrackletPose pose;
    pose.tx = Number(item, "tx");
    pose.ty = Number(item, "ty");
    pose.tz = Number(item, "tz");
    pose.rx = Number(item, "rx");
    pose.ry = Number(item, "ry");
    pose.rz = Number(item, "rz");
    pose.state = Integer(item, "state");
    pose.occlusion = Integer(item, "occlusion");
    pose.truncation = Integer(item, "truncation");
    return pose;
  }

  KittiTracklet Tracklet(const XmlElement& item) const {
    KittiTracklet tracklet;
    tracklet.type = Child(item, "objectType").text;
    if (tracklet.type.empty()) Fail(item, "<objectType> is empty");
    tracklet.h = Number(item, "h");
    tracklet.w = Number(item, "w");
    tracklet.l = Number(item, "l");
    if (!(tracklet.h > 0 && tracklet.w > 0 && tracklet.l > 0)) {
      Fail(item, "the tracklet's h, w and l must be positive");
    }
    tracklet.first_frame = Integer(item, "first_frame");
    if (tracklet.first_frame < 0) Fail(Child(item, "first_frame"), "<first_frame> is negative");
    for (const XmlElement* pose : Items(Child(item, "poses"))) {
      tracklet.poses.push_back(Pose(*pose));
    }
    return tracklet;
  }

 private:
  std::string path_;
};

}  // namespace

XmlElement ParseXmlSubset(const std::string& text, const std::string& what) {
  return XmlReader(text, what).Document();
}

std::vector<KittiTracklet> ReadKittiTracklets(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the tracklet labels");
  std::ostringstream text;
  text << in.rdbuf();
  const XmlElement root = ParseXmlSubset(text.str(), path);
  const TrackletFields fields(path);
  // <boost_serialization><tracklets>...</tracklets></boost_serialization>; the tracklets
  // element alone is read too.
  const XmlElement& tracklets = root.name == "tracklets" ? root : fields.Child(root, "tracklets");
  std::vector<KittiTracklet> out;
  for (const XmlElement* item : fields.Items(tracklets)) out.push_back(fields.Tracklet(*item));
  return out;
}

}  // namespace attend
