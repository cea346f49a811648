// Which kernels the disparity estimator's steps run (stereo/disparity.h): the loops over d are
// written twice, portable and with AVX2 intrinsics, with the same operations in the same order,
// so that both give the same maps bit for bit. Not part of the API that plugins see.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define ATTEND_DISPARITY_AVX2 1
#endif

namespace attend {

// The AVX2 kernels where the processor has AVX2, unless a test asked for the portable ones
// (UsePortableDisparityKernels, stereo/disparity_internal.h). Asked once a row, not a voxel.
bool UseAvx2DisparityKernels();

}  // namespace attend
