// PFM float maps (ground-truth disparity, the dumps `attend eval` and `attend compare` read):
// the input is a PFM file, read with ReadPfm. A map that reads must come back bit for bit
// through WritePfm and ReadPfm.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/pfm.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("input.pfm");
  static const std::string copy = fuzz::ScratchPath("copy.pfm");
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const cv::Mat map = ReadPfm(input);
    WritePfm(copy, map);
    const cv::Mat again = ReadPfm(copy);
    if (again.size() != map.size() || again.type() != map.type()) {
      fuzz::Fail("a PFM changes size or type through WritePfm and ReadPfm");
    }
    for (int row = 0; row < map.rows; ++row) {
      if (std::memcmp(map.ptr(row), again.ptr(row), map.cols * map.elemSize()) != 0) {
        fuzz::Fail("a PFM changes its values through WritePfm and ReadPfm, row " +
                   std::to_string(row));
      }
    }
  });
  return 0;
}
