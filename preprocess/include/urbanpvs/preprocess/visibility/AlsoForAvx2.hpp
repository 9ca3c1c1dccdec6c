// SPDX-License-Identifier: GPL-3.0-or-later
// Marks a function to be built twice, for AVX2 and for the baseline, the build chosen at load
// time (GCC's target_clones). For the bake's widest loops: the rasterizer's rows, the sample
// horizons' sector crossings. Without FMA (not part of the "avx2" target) every operation rounds
// as in the baseline build, so both builds give bit-identical results.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__gnu_linux__)
#define URBANPVS_ALSO_FOR_AVX2 __attribute__((target_clones("avx2", "default")))
#else
#define URBANPVS_ALSO_FOR_AVX2
#endif
