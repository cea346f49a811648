// The disparity estimator's post-processing (stereo/disparity.h): the right view's map for the
// left-right consistency check, the check, and the filling of the pixels it invalidates. The
// check itself and the filling are declared in stereo/disparity_internal.h, for the tests. Not
// part of the API that plugins see.
#pragma once

#include <cstdint>

namespace attend {

// The right view's disparities of one row, winner-take-all over the same correlations: the
// right pixel xr's correlation at d is the left pixel xr + d's, C(xr + d, d); the best d wins,
// the smaller on ties (as OpenCV's SGBM makes its right view for its check). `costs` is the
// row of the volume ([x][d]); `best` and `best_d` are width entries of scratch; `out` gets
// width disparities.
void RightViewRow(const float* costs, int width, int depth, float* best, int32_t* best_d,
                  float* out);

}  // namespace attend
