#pragma once

// KAPFIX_KERNEL marks a hot loop that is built twice, for baseline x86-64 (SSE2) and for AVX2;
// the loader picks the best one the CPU supports, so the shipped binary runs on any x86-64
// board and uses the wider registers where they exist. Off under sanitizers (their runtime
// and ifunc resolvers do not mix) and on other compilers and architectures.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define KAPFIX_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define KAPFIX_KERNEL
#endif
