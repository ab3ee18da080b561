// Loops over wavelengths that the compiler vectorises, built twice where the platform
// allows: for the x86-64 baseline (SSE2, two doubles a lane) and for x86-64-v3 (AVX2 and
// FMA, four), the one to run chosen when the program loads (GCC's target_clones, resolved
// through an ifunc). Elsewhere, and under Clang, the baseline build alone.
//
// A function marked ALLOYCOLOR_SIMD_CLONES keeps to plain loops over raw arrays (no
// library templates inside, which would otherwise be compiled for one target and shared
// by both), and its results differ between the two builds only by rounding: FMA contracts
// a * b + c, the lane sums are taken in another order.
#ifndef ALLOYCOLOR_CORE_SIMD_H_
#define ALLOYCOLOR_CORE_SIMD_H_

// Not under ThreadSanitizer (scripts/tsan.sh): it instruments the ifunc resolver, which the
// loader runs before the sanitizer's runtime has started.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && \
    !defined(__SANITIZE_THREAD__)
#define ALLOYCOLOR_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define ALLOYCOLOR_SIMD_CLONES
#endif

#endif  // ALLOYCOLOR_CORE_SIMD_H_
