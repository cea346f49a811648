// A sweep cell's scores.json (docs/SWEEPS.md), which --collect gathers into sweep.csv and the
// report: the input is the file's text, read with ParseCellScores. Scores that read are a map
// of names to numbers (NaN for null), each name once.
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "app/sweep_records.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  const std::string text = fuzz::ToString(data, size);
  fuzz::ExpectOnlyDocumentedErrors([&] {
    std::set<std::string> names;
    for (const auto& [name, value] : ParseCellScores(text, "cells/c/scores.json")) {
      if (!names.insert(name).second) fuzz::Fail("ParseCellScores gave a score name twice");
      static_cast<void>(value);
    }
  });
  return 0;
}
