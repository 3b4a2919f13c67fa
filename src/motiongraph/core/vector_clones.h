// MG_VECTOR_CLONES on a function with a vectorisable loop: with GCC on x86-64 the function is
// compiled twice, for AVX2 and for the baseline ISA, and the loader picks one for the machine
// (function multi-versioning, target_clones): twice the lanes per instruction where AVX2
// exists, and still one binary for every x86-64. No FMA is enabled, so both versions give
// the same bits. Elsewhere (other compilers, other architectures) it expands to nothing.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define MG_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MG_VECTOR_CLONES
#endif

