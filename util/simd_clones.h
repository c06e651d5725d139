#pragma once
/// NENRIN_AVX2_CLONES before a function: GCC compiles it twice, for AVX2 (8 floats or 4
/// doubles a step) and for the baseline x86-64 (SSE2), and picks one when the program starts;
/// the build sets no -march, so this is how a vectorised loop uses a newer processor. Only
/// loops whose lanes are independent belong under it: both versions then give the same bits
/// (AVX2 alone does not contract a * b + c into an FMA).
/// clang 14 (the sanitizer build) does not emit clones of member functions: one version there.

#if defined(__clang__) || !defined(__x86_64__)
#define NENRIN_AVX2_CLONES
#else
#define NENRIN_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#endif
