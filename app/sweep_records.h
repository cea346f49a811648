// The JSON records of a sweep folder (sweep.json, and each cell's cell.json, status.json and
// scores.json; docs/SWEEPS.md), read with every field's type checked: a record edited by hand
// or cut short is an InputError naming the file and the key ("cells/X/status.json:
// exit_status: expected an integer, found the string "zero""), never a raw parser message.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace attend {

// What a cell's status.json says (docs/SWEEPS.md).
enum class CellState { kWaiting, kRunning, kDone, kFailed, kKilled, kInterrupted };

struct CellStatus {
  CellState state = CellState::kWaiting;
  int exit_status = 0;
  std::string message;   // the error of a failed cell, the cause of a killed one
  double seconds = 0.0;  // wall time of a finished cell
  std::string host;
  long pid = 0;
  std::string executor;    // local or slurm
  std::string slurm_task;  // JOB_TASK of a Slurm array task
};

// The size of a record read whole (docs/LIMITS.md): a sweep.json of the largest sweep
// (kMaxSweepCells cells) is a few MB.
inline constexpr std::uintmax_t kMaxSweepRecordBytes = 64u << 20;

// One JSON object of a record file, or a map or list element inside one (its key path then
// starts the messages: "cells[3].name").
class SweepRecord {
 public:
  // Parses `text`, the content of `file`. InputError when it is not JSON or not an object.
  SweepRecord(const std::string& text, std::string file);
  // Reads `file`, a regular file of at most kMaxSweepRecordBytes (util/file_checks.h).
  static SweepRecord Load(const std::string& file);

  bool Has(const std::string& key) const;
  // Required fields, and optional ones with a default when absent; a field of another type
  // (or an integer out of [min, max]) is an InputError naming the file and the key.
  std::string String(const std::string& key) const;
  std::string String(const std::string& key, const std::string& absent) const;
  long Integer(const std::string& key, long min, long max) const;
  long Integer(const std::string& key, long min, long max, long absent) const;
  double Number(const std::string& key, double absent) const;  // finite, >= 0
  std::vector<std::string> Strings(const std::string& key) const;
  std::vector<std::vector<std::string>> StringLists(const std::string& key) const;
  std::vector<std::vector<int>> IntLists(const std::string& key, const std::vector<std::vector<int>>& absent) const;
  // A map of strings, in file order.
  std::vector<std::pair<std::string, std::string>> StringMap(const std::string& key) const;
  SweepRecord Object(const std::string& key) const;
  std::vector<SweepRecord> Objects(const std::string& key) const;

  const nlohmann::ordered_json& json() const { return json_; }
  const std::string& file() const { return file_; }
  // Throws InputError "FILE: KEYPATH: message".
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const;

 private:
  SweepRecord(nlohmann::ordered_json json, std::string file, std::string path);
  const nlohmann::ordered_json& Field(const std::string& key) const;  // present
  std::string KeyPath(const std::string& key) const;

  nlohmann::ordered_json json_;
  std::string file_;
  std::string path_;  // "" at the top
};

// Why nothing can be written below `folder` when it is so ("the disk is full", ...), else "".
std::string WhyUnwritable(const std::string& folder);

// A cell's status.json (`text`, read from `file`): its state, one of running, done, failed,
// killed, interrupted, and the typed fields of CellStatus.
CellStatus ParseCellStatus(const std::string& text, const std::string& file);

// A cell's scores.json: an object of scores, each a number or null (an undefined score, NaN).
std::vector<std::pair<std::string, double>> ParseCellScores(const std::string& text,
                                                            const std::string& file);

}  // namespace attend
