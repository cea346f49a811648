// The skin model file (configs/skin_tsl.yaml; the skin feature's `model` key): the input is the
// file, read with LoadSkinModel. A model that loads must come back unchanged through
// SaveSkinModel, which promises that every number reads back exactly.
#include <cstddef>
#include <cstdint>
#include <string>

#include "io/skin_files.h"
#include "fuzz/fuzz_support.h"

namespace {

// The first field that differs, "" when none does.
std::string FirstDifference(const attend::SkinModel& a, const attend::SkinModel& b) {
  const attend::SkinModel::Provenance& p = a.provenance;
  const attend::SkinModel::Provenance& q = b.provenance;
  if (a.mean != b.mean) return "mean";
  if (a.covariance != b.covariance) return "covariance";
  if (a.threshold != b.threshold) return "threshold";
  if (p.command != q.command) return "training.command";
  if (p.data != q.data) return "training.data";
  if (p.rule != q.rule) return "training.rule";
  if (p.skin_samples != q.skin_samples) return "training.skin_samples";
  if (p.nonskin_samples != q.nonskin_samples) return "training.nonskin_samples";
  if (p.holdout_fraction != q.holdout_fraction) return "training.holdout_fraction";
  if (p.seed != q.seed) return "training.seed";
  if (p.training_tpr != q.training_tpr) return "training.training_tpr";
  if (p.training_fpr != q.training_fpr) return "training.training_fpr";
  if (p.holdout_tpr != q.holdout_tpr) return "training.holdout_tpr";
  if (p.holdout_fpr != q.holdout_fpr) return "training.holdout_fpr";
  return "";
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("input.yaml");
  static const std::string copy = fuzz::ScratchPath("copy.yaml");
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const SkinModel model = LoadSkinModel(input);
    const SkinClassifier classifier(model);
    classifier.IsSkin(0.5, 100.0);
    SaveSkinModel(model, copy);
    SkinModel again;
    try {
      again = LoadSkinModel(copy);
    } catch (const Error& e) {
      fuzz::Fail(std::string("a saved skin model does not load back: ") + e.what());
    }
    const std::string field = FirstDifference(model, again);
    if (!field.empty()) fuzz::Fail("a skin model's " + field + " changes through SaveSkinModel");
  });
  return 0;
}
