// The options of the saliency map (saliency/saliency.h); their field table, check and names
// are in saliency.cc. A header of its own, so that the normalisations' table
// (normalisation.h), whose functions read these options, does not include the stage that
// applies them.
#pragma once

#include <string>
#include <vector>

#include "util/option_fields.h"

namespace attend {

// How the normalised feature maps combine (SaliencyOptions::combination).
enum class SaliencyCombination { kSum, kProduct };

struct SaliencyOptions {
  std::string normalisation = "minmax";  // one of Normalisations()
  int local_maxima_window = 15;          // odd window side in pixels, for local_maxima
  // The combined map is blurred by a Gaussian of this share of the image's larger side (0:
  // none), then scaled back to its maximum. Region-based features are piecewise constant with
  // hard edges, and people look near a salient thing, not exactly at it; not in the
  // thesis.
  double blur = 0.0;
  // The combined map, after its blur, scaled to a maximum of 1 and raised to this power (a
  // pointwise calibration that keeps the
  // order of its values, so every AUC; NSS and CC prefer a map as peaked as the fixations'
  // density). 1: the map as it is; not in the thesis.
  double gamma = 1.0;
  // How the normalised maps combine: sum (SPEC 2.3, the thesis: the weighted mean) or
  // product (the weighted geometric mean, prod_i (n_i + 0.01)^(w_i / sum w), less its value
  // where every map is 0: a map that is low somewhere, such as a centre bias, vetoes there
  // rather than only adding elsewhere; not in the thesis).
  SaliencyCombination combination = SaliencyCombination::kSum;

  // The built-in normalisations' names (BuiltinNormalisations, saliency/normalisation.h).
  static const std::vector<std::string>& Normalisations();
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the configuration apply.
  static const OptionFields<SaliencyOptions>& Fields();
};

}  // namespace attend
