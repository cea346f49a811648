// What the tests of attend sweep share (tests/cli/sweep_cli_test.cc, sweep_slurm_test.cc): the
// rendered scenes, the 2 x 2 grid over them, and readers of a sweep folder.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace attend::testing {

// Renders the bundled lab and occlusions scenes, 4 frames each, into dir/lab and
// dir/occlusions (each with gt/objects.csv).
inline void RenderSweepScenes(const TempDir& dir) {
  for (const char* scene : {"lab", "occlusions"}) {
    const std::string file =
        (std::filesystem::path(ProjectRoot()) / "sequences" / (std::string(scene) + ".yaml"))
            .string();
    const Result r = Attend(dir, {"synth", file, "--out", scene, "--frames", "4", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
  }
}

// The 2 x 2 grid of the tests: a feature weight and the targets a frame may start, over two
// scenes: 8 cells.
inline std::string GridSweep(const std::string& first, const std::string& second) {
  return "# 2 x 2 over two rendered scenes\n"
         "set:\n  threads: 1\n"
         "grid:\n"
         "  features.colour_contrast.weight: [0.5, 1.0]\n"
         "  select.max_new: [1, 3]\n"
         "inputs:\n"
         "  - sequence: " + first + "\n"
         "  - sequence: " + second + "\n";
}

// The rows of a CSV file without quoted fields, by column name.
inline std::vector<std::map<std::string, std::string>> ReadCsv(const std::string& path) {
  std::istringstream lines(ReadText(path));
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  const auto split = [](const std::string& text) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(text);
    while (std::getline(in, field, ',')) fields.push_back(field);
    if (!text.empty() && text.back() == ',') fields.push_back("");
    return fields;
  };
  while (std::getline(lines, line)) {
    if (header.empty()) {
      header = split(line);
      continue;
    }
    const std::vector<std::string> fields = split(line);
    EXPECT_EQ(fields.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < fields.size(); ++i) row[header[i]] = fields[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

// The cell folders of a sweep whose status.json says done.
inline std::vector<std::string> DoneCells(const std::string& sweep) {
  std::vector<std::string> done;
  std::error_code error;
  const std::filesystem::path cells = std::filesystem::path(sweep) / "cells";
  if (!std::filesystem::is_directory(cells, error)) return done;
  for (const auto& entry : std::filesystem::directory_iterator(cells, error)) {
    if (Contains(ReadText((entry.path() / "status.json").string()), "\"state\": \"done\"")) {
      done.push_back(entry.path().string());
    }
  }
  std::sort(done.begin(), done.end());
  return done;
}

}  // namespace attend::testing
