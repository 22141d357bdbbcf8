#include "src/core/depth_key.hpp"

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include <stdexcept>

#include "src/core/framebuffer.hpp"

namespace lzb {

bool wideKeysSupported() {
#if defined(__x86_64__)
  unsigned a, b, c, d;
  return __get_cpuid(1, &a, &b, &c, &d) && (c & bit_CMPXCHG16B);
#else
  return true;
#endif
}

void KeyBuffer::reset(int width, int height, bool wide, int threads) {
  if (wide && !wideKeysSupported())
    throw std::runtime_error("this CPU has no 16-byte compare-and-swap for 128-bit keys");
  width_ = width;
  height_ = height;
  wide_ = wide;
  const long n = long(width) * long(height);
  if (wide) {
    narrow_.clear();
    wide_keys_.resize(size_t(n));
    WideKey* k = wide_keys_.data();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) k[i] = kEmptyWideKey;
  } else {
    wide_keys_.clear();
    narrow_.resize(size_t(n));
    uint64_t* k = narrow_.data();
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) k[i] = kEmptyKey;
  }
}

void KeyBuffer::resolve(Framebuffer& fb, int threads) const {
  const long n = long(width_) * long(height_);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < n; ++i) {
    uint64_t hi, lo;
    bool empty;
    if (wide_) {
      hi = wide_keys_[size_t(i)].hi;
      lo = wide_keys_[size_t(i)].lo;
      empty = hi == kEmptyWideKey.hi;
    } else {
      hi = narrow_[size_t(i)] >> 32;
      lo = narrow_[size_t(i)] & 0xffffffffu;
      empty = narrow_[size_t(i)] == kEmptyKey;
    }
    fb.depth[size_t(i)] = empty ? kEmptyDepth : std::bit_cast<float>(uint32_t(hi));
    fb.id[size_t(i)] = empty ? kNoId : lo;
  }
}

}  // namespace lzb
