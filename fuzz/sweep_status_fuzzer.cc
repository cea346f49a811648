// A sweep cell's status.json (docs/SWEEPS.md), which `attend sweep DIR --status`, --collect,
// a resumed sweep and the local executor read: the input is the file's text, read with
// ParseCellStatus. A record that reads has a known state and an exit status of a process.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/sweep_folder.h"
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
    const CellStatus status = ParseCellStatus(text, "cells/c/status.json");
    if (status.exit_status < 0 || status.exit_status > 255) {
      fuzz::Fail("ParseCellStatus accepted an exit status outside 0..255");
    }
    if (!(status.seconds >= 0.0)) fuzz::Fail("ParseCellStatus accepted a negative or NaN time");
    CellStateName(status.state);
  });
  return 0;
}
