// The HTML report of `attend sweep DIR --collect` (docs/SWEEPS.md), built from the same page
// pieces as attend report and attend compare (eval/html_page.h): the cells in a table sortable
// by any score, each score against each swept parameter (means over the other cells with that
// value, and their spread), and the best configuration for each score, ready to copy.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "eval/html_page.h"

namespace attend {

struct SweepReportCell {
  std::string name;
  std::string input;
  std::vector<std::string> settings;  // the swept keys' values, in SweepReportInput::keys order
  std::string state;                  // done, failed, killed, running, waiting
  std::string message;                // a failed or killed cell's reason
  double seconds = 0.0;
  std::map<std::string, double> scores;  // NaN: no value
  std::string config;                    // the base configuration file ("" for track)
  std::vector<std::string> sets;         // its --set words: the fixed sets, then its settings
  std::string config_yaml;               // its effective configuration
};

struct SweepReportInput {
  std::string dir;
  std::string command;  // run, track or saliency
  std::string command_line;
  std::vector<std::string> keys;
  // Keys swept together (a zip group) are plotted together; a grid key alone. Indexes into
  // `keys`; empty: each key alone.
  std::vector<std::vector<int>> groups;
  std::vector<std::string> scores;  // score names, in the scorers' order
  std::vector<SweepReportCell> cells;
  std::vector<std::string> notes;
  ChartLibrary chart;
};

// Whether a lower value of score `name` is the better one (latencies, errors, switches,
// divergences, times); otherwise higher is better.
bool LowerIsBetter(const std::string& name);

// The best configuration for each score that differs between configurations (context fields
// such as frames and objects left out): the one whose mean over its done cells is best, ties
// to the first in sweep order. Configurations are the distinct settings.
struct BestConfiguration {
  std::string score;
  std::vector<std::string> settings;
  double mean = 0.0;
  int cells = 0;  // done cells it was averaged over
};
std::vector<BestConfiguration> BestConfigurations(const SweepReportInput& input);

std::string SweepReportHtml(const SweepReportInput& input);

}  // namespace attend
