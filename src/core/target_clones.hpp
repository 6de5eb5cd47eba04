#pragma once
// SHPB_TARGET_CLONES: a loop over contiguous arrays compiled twice, for AVX2 and for the baseline
// x86-64, the loader picking the one the CPU runs (GCC/Clang function multiversioning): twice the
// doubles per instruction, the same IEEE operations in the same order (neither target enables FMA,
// so no contraction), hence bit-identical results on every machine. Off under AddressSanitizer.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && \
    !defined(__SANITIZE_ADDRESS__)
#define SHPB_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SHPB_TARGET_CLONES
#endif
