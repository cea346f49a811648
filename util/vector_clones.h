// ATTEND_VECTOR_CLONES marks a function to be compiled twice, for AVX2 and for the baseline
// x86-64 (SSE2), the processor picking one at run time. Only the vector width differs: the same
// operations in the same order (no FMA, which "avx2" does not enable), so the same results on
// every machine. Elsewhere it marks nothing.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__)
#define ATTEND_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ATTEND_VECTOR_CLONES
#endif
