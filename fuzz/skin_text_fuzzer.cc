// The skin training text of `attend skin-train` ("B G R label" lines, the UCI Skin
// Segmentation format): the input is the file, read with ReadSkinText, and then trained on as
// skin-train trains (the split of SkinSplit, FitSkinModel with both threshold rules,
// EvaluateSkinModel on the held-out part, SaveSkinModel). A model it saves must load back.
#include <cstddef>
#include <cstdint>
#include <string>

#include "features/skin_training.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("skin.txt");
  static const std::string model_path = fuzz::ScratchPath("skin_model.yaml");
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  SkinSplit split;
  bool read = false;
  fuzz::ExpectOnlyDocumentedErrors([&] {
    ReadSkinText(input, split.Sink());
    read = true;
  });
  if (!read) return 0;
  for (const char* rule : {"youden", "tpr:0.95"}) {
    fuzz::ExpectOnlyDocumentedErrors([&] {
      const SkinModel model = FitSkinModel(split.training, ThresholdRule::Parse(rule));
      EvaluateSkinModel(model, split.held_out);
      SaveSkinModel(model, model_path);
      try {
        LoadSkinModel(model_path);
      } catch (const Error& e) {
        fuzz::Fail(std::string("a trained skin model does not load back: ") + e.what());
      }
    });
  }
  return 0;
}
