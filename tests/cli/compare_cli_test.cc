// attend compare and attend report end to end (SPEC 3.2, 4; docs/COMPARE.md): a run against
// its exact copy, against a run with one feature weight changed, the single-run report, the
// exit statuses of bad input, and the report rendered by headless Chromium.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

// Three short runs of the bundled lab scene, made once for the suite: a, its copy, and b with
// features.colour_contrast.weight changed.
class CompareCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const std::string scene =
        (fs::path(testing::ProjectRoot()) / "sequences" / "lab.yaml").string();
    Result r = Attend(*dir_, {"synth", scene, "--out", "seq", "--frames", "4"});
    ASSERT_EQ(r.status, 0) << r.err;
    // The thesis's nearness score: its saliency maps are dark purple over most of the frame in
    // the report's false colour, which the rendering test below counts (depth contrast, the
    // default, leaves the wall at 0, drawn black like the page's text).
    const std::vector<std::string> run = {"run",   "--sequence",
                                          "seq",   "--frames",
                                          "0:3",   "--quiet",
                                          "--set", "output.dump=[saliency,overlay]",
                                          "--set", "features.disparity.score=nearness"};
    std::vector<std::string> a = run;
    a.insert(a.end(), {"--out", "a"});
    r = Attend(*dir_, a);
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<std::string> b = run;
    b.insert(b.end(), {"--out", "b", "--set", "features.colour_contrast.weight=0.25"});
    r = Attend(*dir_, b);
    ASSERT_EQ(r.status, 0) << r.err;
    fs::copy(dir_->path() / "a", dir_->path() / "a_copy", fs::copy_options::recursive);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  static std::string Run(const std::string& name) { return dir_->File(name); }

  static nlohmann::json Summary(const std::string& out) {
    return nlohmann::json::parse(ReadText((fs::path(out) / "summary.json").string()));
  }

  static TempDir* dir_;
};

TempDir* CompareCli::dir_ = nullptr;

TEST_F(CompareCli, RunAgainstItsCopyIsPerfect) {
  const TempDir out;
  const Result r = Attend(out, {"compare", Run("a"), Run("a_copy"), "--out", "cmp"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no notes
  const nlohmann::json summary = Summary(out.File("cmp"));
  ASSERT_EQ(summary["comparisons"].size(), 1u);
  const nlohmann::json& c = summary["comparisons"][0];
  EXPECT_EQ(c["config_differences"].size(), 0u) << c["config_differences"].dump();
  EXPECT_EQ(c["common_frames"], 4);
  EXPECT_NEAR(c["saliency_mean"]["cc"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(c["saliency_mean"]["sim"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(c["saliency_mean"]["kl"].get<double>(), 0.0, 1e-9);
  for (const auto& frame : c["frames"]) {
    EXPECT_NEAR(frame["cc"].get<double>(), 1.0, 1e-9);
    EXPECT_EQ(frame["matched"], frame["targets_a"]);
  }
  EXPECT_GT(c["targets"]["matched"].size(), 0u);
  EXPECT_EQ(c["targets"]["only_a"].size(), 0u);
  EXPECT_EQ(c["targets"]["only_b"].size(), 0u);
  EXPECT_TRUE(c["targets"]["same_order"].get<bool>());
  EXPECT_EQ(c["targets"]["order_a"], c["targets"]["order_b"]);
  const std::string html = ReadText(out.File("cmp/report.html"));
  EXPECT_TRUE(Contains(html, "None: the runs have the same configuration")) << html.size();
}

TEST_F(CompareCli, OneChangedWeightIsTheOnlyDifference) {
  const TempDir out;
  const Result r = Attend(out, {"compare", Run("a"), Run("b"), Run("a_copy"), "--out", "cmp"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json summary = Summary(out.File("cmp"));
  ASSERT_EQ(summary["comparisons"].size(), 2u);
  const nlohmann::json& diff = summary["comparisons"][0]["config_differences"];
  ASSERT_EQ(diff.size(), 1u) << diff.dump();
  EXPECT_EQ(diff[0]["key"], "features.colour_contrast.weight");
  EXPECT_EQ(diff[0]["b"], "0.25");
  EXPECT_EQ(summary["comparisons"][1]["config_differences"].size(), 0u);
  // A changed weight changes the saliency maps.
  EXPECT_LT(summary["comparisons"][0]["saliency_mean"]["cc"].get<double>(), 0.999999);
  // The sequence has ground truth: each run is scored as attend eval scores it.
  for (const char* run : {"a", "b"}) {
    const Result eval = Attend(out, {"eval", Run(run)});
    ASSERT_EQ(eval.status, 0) << eval.err;
    const nlohmann::json scores = nlohmann::json::parse(eval.out);
    const nlohmann::json& attention = summary["runs"][run == std::string("a") ? 0 : 1]["attention"];
    ASSERT_FALSE(attention.is_null()) << run;
    EXPECT_EQ(attention["coverage"], scores["coverage"]) << run;
    EXPECT_EQ(attention["attended"], scores["attended"]) << run;
    EXPECT_EQ(attention["mean_iou"], scores["mean_iou"]) << run;
  }
  const std::string html = ReadText(out.File("cmp/report.html"));
  EXPECT_TRUE(Contains(html, "features.colour_contrast.weight"));
  EXPECT_TRUE(Contains(html, "data:image/png;base64,"));
  // The report is self-contained: nothing is fetched from elsewhere.
  EXPECT_FALSE(Contains(html, "src=\"http"));
  EXPECT_FALSE(Contains(html, "<script src"));
}

TEST_F(CompareCli, ReportOfOneRun) {
  const TempDir out;
  const Result r = Attend(out, {"report", Run("a"), "--out", "rep"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json summary = Summary(out.File("rep"));
  EXPECT_EQ(summary["runs"].size(), 1u);
  EXPECT_EQ(summary["runs"][0]["frames"], 4);
  EXPECT_EQ(summary["comparisons"].size(), 0u);
  const std::string html = ReadText(out.File("rep/report.html"));
  EXPECT_TRUE(Contains(html, "attend report"));
  EXPECT_TRUE(Contains(html, "data:image/png;base64,"));
}

TEST_F(CompareCli, BadInputExitsWithItsStatus) {
  const TempDir out;
  fs::create_directories(out.path() / "not_a_run");
  Result r = Attend(out, {"compare", Run("a"), "not_a_run", "--out", "cmp"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "attend: error: not_a_run: not a run folder (no frames.jsonl)"))
      << r.err;
  r = Attend(out, {"compare", Run("a"), "nowhere", "--out", "cmp"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "nowhere")) << r.err;
  r = Attend(out, {"compare", Run("a"), "--out", "cmp"});  // one run
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(out, {"compare", Run("a"), Run("b")});  // no --out
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(out, {"report", Run("a"), Run("b"), "--out", "rep"});
  EXPECT_EQ(r.status, 2) << r.err;
  // An occupied output folder needs --overwrite, which replaces an earlier report only.
  fs::create_directories(out.path() / "busy");
  out.Write("busy/notes.txt", "mine");
  r = Attend(out, {"compare", Run("a"), Run("b"), "--out", "busy"});
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(out, {"compare", Run("a"), Run("b"), "--out", "cmp"});
  EXPECT_EQ(r.status, 0) << r.err;
  r = Attend(out, {"compare", Run("a"), Run("b"), "--out", "cmp"});
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(out, {"compare", Run("a"), Run("b"), "--out", "cmp", "--overwrite"});
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST_F(CompareCli, RunWithoutSaliencyDumpsGivesANote) {
  const TempDir out;
  fs::copy(fs::path(Run("a")), out.path() / "no_maps", fs::copy_options::recursive);
  fs::remove_all(out.path() / "no_maps" / "saliency");
  const Result r = Attend(out, {"compare", Run("a"), "no_maps", "--out", "cmp"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "lack a saliency map")) << r.err;
  const nlohmann::json summary = Summary(out.File("cmp"));
  EXPECT_TRUE(summary["comparisons"][0]["saliency_mean"].is_null());
  EXPECT_TRUE(Contains(ReadText(out.File("cmp/report.html")), "lack a saliency map"));
}

TEST_F(CompareCli, ChartsWithoutDataAreLeftOut) {
  const TempDir out;
  fs::copy(fs::path(Run("a")), out.path() / "no_maps", fs::copy_options::recursive);
  fs::remove_all(out.path() / "no_maps" / "saliency");
  const Result r = Attend(out, {"compare", Run("a"), "no_maps", "--out", "cmp"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = ReadText(out.File("cmp/report.html"));
  if (!Contains(html, "Chart.js was not found")) {
    // No saliency metrics to draw; timings and targets are there.
    EXPECT_FALSE(Contains(html, "id=\"chart-cc\"")) << "an empty CC chart";
    EXPECT_FALSE(Contains(html, "id=\"chart-kl\""));
    EXPECT_TRUE(Contains(html, "id=\"chart-timings\""));
    EXPECT_TRUE(Contains(html, "id=\"chart-targets\""));
  }
  const Result with_maps = Attend(out, {"compare", Run("a"), Run("b"), "--out", "cmp2"});
  ASSERT_EQ(with_maps.status, 0) << with_maps.err;
  const std::string full = ReadText(out.File("cmp2/report.html"));
  if (!Contains(full, "Chart.js was not found")) {
    EXPECT_TRUE(Contains(full, "id=\"chart-cc\""));
  }
}

TEST_F(CompareCli, GtScoresARunWhoseSourceHasNone) {
  // The same frames as a plain folder of images, whose run has no sequence folder and so no gt/.
  const TempDir out;
  Result r = Attend(out, {"run", "--images", dir_->File("seq/left"), "--frames", "0:3", "--quiet",
                          "--set", "features=[{name: colour_contrast}]", "--out", "images"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(out, {"report", "images", "--out", "plain"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Summary(out.File("plain"))["runs"][0]["attention"].is_null());
  r = Attend(out, {"report", "images", "--gt", dir_->File("seq/gt"), "--out", "scored"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json summary = Summary(out.File("scored"));
  ASSERT_FALSE(summary["runs"][0]["attention"].is_null()) << summary.dump();
  EXPECT_GT(summary["runs"][0]["attention"]["objects"].get<int>(), 0);
  EXPECT_TRUE(Contains(summary["runs"][0]["ground_truth"].get<std::string>(), "objects.csv"));
  // One --gt a run, in their order, for compare; a count that fits neither is refused.
  r = Attend(out, {"compare", "images", Run("a"), "--gt", dir_->File("seq/gt"), "--gt",
                   dir_->File("seq/gt"), "--out", "both"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(Summary(out.File("both"))["runs"][0]["attention"].is_null());
  r = Attend(out, {"compare", "images", Run("a"), Run("b"), "--gt", "x", "--gt", "y", "--out",
                   "bad"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--gt given 2 times for 3 runs")) << r.err;
  r = Attend(out, {"report", "images", "--gt", out.File("nowhere"), "--out", "missing"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "objects.csv")) << r.err;
}

// The chromium program on PATH, "" when there is none.
std::string FindChromium() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    for (const char* name : {"chromium", "chromium-browser"}) {
      const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      std::error_code error;
      if (fs::is_regular_file(candidate, error)) return candidate.string();
    }
    start = end + 1;
  }
  return "";
}

// Pixels within `tolerance` of `colour` (BGR) in every channel.
int CountColour(const cv::Mat& image, const cv::Vec3b& colour, int tolerance) {
  int count = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - colour[0]) <= tolerance && std::abs(p[1] - colour[1]) <= tolerance &&
          std::abs(p[2] - colour[2]) <= tolerance) {
        ++count;
      }
    }
  }
  return count;
}

TEST_F(CompareCli, ReportRendersInHeadlessChromium) {
  const std::string chromium = FindChromium();
  if (chromium.empty()) {
    GTEST_SKIP() << "chromium is not installed, so the report is not rendered; install it with "
                    "scripts/install_deps.sh (Debian package chromium)";
  }
  if (!fs::exists("/usr/share/javascript/chart.js/chart.min.js")) {
    GTEST_SKIP() << "libjs-chart.js is not installed, so the report has no charts to render; "
                    "install it with scripts/install_deps.sh";
  }
  const TempDir out;
  Result r = Attend(out, {"compare", Run("a"), Run("b"), "--out", "cmp"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string shot = out.File("shot.png");
  r = testing::Run(
      chromium, out,
      {"--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
       "--user-data-dir=" + out.File("profile"), "--window-size=1280,2200", "--screenshot=" + shot,
       "file://" + fs::absolute(out.File("cmp/report.html")).string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const cv::Mat image = cv::imread(shot, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty()) << "no screenshot: " << r.err;
  // Not blank: a good share of the page is not the white background.
  const int white = CountColour(image, {255, 255, 255}, 8);
  EXPECT_GT(image.total() - white, image.total() / 20) << shot;
  // The charts are drawn: run B's colour (#d62728, the CC, SIM and KL lines and the timing
  // bars) covers many pixels; nothing else on the page has it.
  EXPECT_GT(CountColour(image, {40, 39, 214}, 12), 500);
  // The images are drawn: the saliency thumbnails' false colour (inferno) is mostly dark
  // purple, which nothing else on the page is.
  int purple = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      const cv::Vec3b p = image.at<cv::Vec3b>(y, x);  // BGR
      purple += p[0] > p[2] + 20 && p[0] > p[1] + 40 && p[0] + p[1] + p[2] < 300;
    }
  }
  EXPECT_GT(purple, 20000) << shot;
}

// How often each element that makes a page's structure occurs in Chromium's DOM of `html`
// (--dump-dom: the document after its scripts ran), and the page's title.
struct PageShape {
  std::map<std::string, int> elements;
  std::string title;
  std::string dom;
};

PageShape RenderedShape(const std::string& chromium, const TempDir& dir, const std::string& html) {
  const Result r = testing::Run(
      chromium, dir,
      {"--headless", "--no-sandbox", "--disable-gpu", "--user-data-dir=" + dir.File("profile"),
       "--dump-dom", "file://" + fs::absolute(html).string()});
  EXPECT_EQ(r.status, 0) << r.err;
  PageShape shape;
  shape.dom = r.out;
  for (const char* tag : {"<section", "<table", "<tr", "<canvas", "<script", "<img", "<h2"}) {
    int count = 0;
    for (size_t at = r.out.find(tag); at != std::string::npos; at = r.out.find(tag, at + 1)) ++count;
    shape.elements[tag] = count;
  }
  const size_t open = r.out.find("<title>"), close = r.out.find("</title>");
  if (open != std::string::npos && close != std::string::npos) {
    shape.title = r.out.substr(open + 7, close - open - 7);
  }
  return shape;
}

// Run folders named, and a sequence named, to break out of the page's elements (issue 46: a
// folder named y<!--<script> made the chart's <script> swallow the rest of the page).
TEST_F(CompareCli, HostileNamesCannotChangeTheReportsStructureInChromium) {
  const std::string chromium = FindChromium();
  if (chromium.empty()) {
    GTEST_SKIP() << "chromium is not installed; install it with scripts/install_deps.sh";
  }
  const TempDir out;
  const std::vector<std::string> names = {"y<!--<script>",
                                          "q\"><img src=x onerror=\"document.title='PWNED'\">",
                                          "javascript:document.title='PWNED'"};
  // Copies of run b under each name with a sequence of that name, and plain ones beside them.
  const auto copy_of_b = [&](const std::string& name, const std::string& sequence) {
    const fs::path copy = out.path() / name;
    fs::copy(Run("b"), copy, fs::copy_options::recursive);
    nlohmann::json summary = nlohmann::json::parse(ReadText((copy / "summary.json").string()));
    summary["sequence"]["name"] = sequence;
    std::ofstream((copy / "summary.json").string()) << summary.dump();
    return copy.string();
  };
  std::vector<std::string> hostile = {"compare", Run("a")}, plain = {"compare", Run("a")};
  for (size_t i = 0; i < names.size(); ++i) {
    hostile.push_back(copy_of_b(
        names[i], "</script><script>document.title='PWNED'</script><!--<script>\u2028"));
    plain.push_back(copy_of_b("plain" + std::to_string(i), "plain"));
  }
  hostile.insert(hostile.end(), {"--out", "hostile"});
  plain.insert(plain.end(), {"--out", "clean"});
  Result r = Attend(out, hostile);
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(out, plain);
  ASSERT_EQ(r.status, 0) << r.err;
  const PageShape clean = RenderedShape(chromium, out, out.File("clean/report.html"));
  const PageShape page = RenderedShape(chromium, out, out.File("hostile/report.html"));
  EXPECT_GT(clean.elements.at("<section"), 3);
  EXPECT_EQ(page.elements, clean.elements);
  EXPECT_EQ(page.title, clean.title);
  EXPECT_FALSE(Contains(page.title, "PWNED"));
  // The names are shown as text.
  EXPECT_TRUE(Contains(page.dom, "y&lt;!--&lt;script&gt;")) << page.dom.substr(0, 2000);
  EXPECT_TRUE(Contains(page.dom, "&lt;/script&gt;&lt;script&gt;document.title="));
  // The single-run report too.
  r = Attend(out, {"report", hostile[2], "--out", "single"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(out, {"report", plain[2], "--out", "single_clean"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(RenderedShape(chromium, out, out.File("single/report.html")).elements,
            RenderedShape(chromium, out, out.File("single_clean/report.html")).elements);
}

}  // namespace
}  // namespace attend
