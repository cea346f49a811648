#include "app/train_skin_model.h"

#include <filesystem>
#include <system_error>

#include "io/skin_files.h"
#include "util/error.h"
#include "util/strings.h"
#include "util/timer.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

nlohmann::json Rate(double rate) { return rate >= 0.0 ? nlohmann::json(rate) : nlohmann::json(); }

nlohmann::json Rates(const SkinRates& rates) {
  return {{"tpr", Rate(rates.tpr)},
          {"fpr", Rate(rates.fpr)},
          {"skin", rates.skin},
          {"nonskin", rates.nonskin}};
}

}  // namespace

nlohmann::json TrainSkinModel(const SkinTrainRequest& request) {
  const Stopwatch watch;
  const ThresholdRule& rule = request.rule;
  const std::string& command_line = request.command_line;
  std::error_code error;
  if (fs::is_directory(request.out, error)) {
    throw OutputError(request.out + ": is a folder; --out names the model file to write");
  }
  if (fs::exists(request.out, error) && !request.overwrite) {
    throw OutputError(request.out + ": already exists (pass --overwrite to replace it)");
  }

  SkinSplit split;
  split.seed = request.seed;
  split.holdout_fraction = request.holdout;
  const SkinSampleSink sink = split.Sink();
  for (const std::string& item : request.data) ReadSkinData(item, sink);
  const double read_ms = watch.ElapsedMs();
  const size_t skin = split.training.skin.size() + split.held_out.skin.size();
  if (skin == 0) {
    throw InputError(Join(request.data, " ") +
                     ": the data holds no skin samples (label 1, or non-zero mask pixels)");
  }

  SkinModel model = FitSkinModel(split.training, rule);
  const SkinRates training = EvaluateSkinModel(model, split.training);
  const SkinRates held_out = EvaluateSkinModel(model, split.held_out);
  SkinModel::Provenance& provenance = model.provenance;
  provenance.command = command_line;
  provenance.data = Join(request.data, " ");
  provenance.holdout_fraction = request.holdout;
  provenance.seed = request.seed;
  provenance.holdout_tpr = held_out.tpr;
  provenance.holdout_fpr = held_out.fpr;
  // The folder is made only now, so that bad data leaves nothing behind.
  const fs::path parent = fs::path(request.out).parent_path();
  if (!parent.empty()) {
    fs::create_directories(parent, error);
    if (error) {
      throw OutputError(parent.string() + ": cannot create the folder (" + error.message() + ")");
    }
  }
  SaveSkinModel(model, request.out);

  const Eigen::Matrix2d& c = model.covariance;
  const nlohmann::json report = {
      {"model", request.out},
      {"samples",
       {{"skin", skin},
        {"nonskin", split.training.nonskin.size() + split.held_out.nonskin.size()}}},
      {"mean", {model.mean[0], model.mean[1]}},
      {"covariance", {c(0, 0), c(0, 1), c(1, 0), c(1, 1)}},
      {"threshold", model.threshold},
      {"rule", provenance.rule},
      {"holdout_fraction", request.holdout},
      {"seed", request.seed},
      {"train", Rates(training)},
      {"holdout", Rates(held_out)},
      {"milliseconds", {{"read", read_ms}, {"total", watch.ElapsedMs()}}}};
  return report;
}

}  // namespace attend
