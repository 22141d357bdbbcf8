#pragma once
// A read prefetch the optimiser keeps: at -O2 GCC's dead-code elimination drops a
// __builtin_prefetch whose address comes from loads made only for it (shading.cpp's look-ahead).

namespace lzb {

inline void prefetchRead(const void* p) {
#if defined(__x86_64__) || defined(__i386__)
  asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
  __builtin_prefetch(p);
#endif
}

}  // namespace lzb
