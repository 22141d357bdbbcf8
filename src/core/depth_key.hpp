#pragma once
// The compositing key: the one "nearer" rule of every pass, thread and rank.
//
// A sample is (view depth, expanded triangle ID). Sample a is nearer than sample b when its depth
// is smaller, or the depths are equal and its ID is smaller. Depths are positive floats, +inf
// where empty (camera.hpp), and positive floats order like their bit patterns, so the rule is
// the integer order of the packed key
//   narrow: (depth bits << 32) | ID      64 bits, scenes of fewer than 2^32 expanded triangles
//   wide:   (depth bits, 64-bit ID)      128 bits, any scene
// and a per-pixel minimum of keys (an atomic minimum between threads, one pass after another,
// MPI_MIN between ranks) gives one result whatever the order. Framebuffer::keepNearer, the MPI
// reduction, the native z-buffer, the splatting core and every Embree query (ties at equal t,
// raycast/exact/embree_level.hpp) all use nearer() or these keys.
#include <atomic>
#include <bit>
#include <cstdint>
#include <vector>

namespace lzb {

struct Framebuffer;

inline uint32_t depthBits(float depth) { return std::bit_cast<uint32_t>(depth); }

// True when (depth, id) is nearer than (thanDepth, thanId): the one rule.
inline bool nearer(float depth, uint64_t id, float thanDepth, uint64_t thanId) {
  const uint32_t a = depthBits(depth), b = depthBits(thanDepth);
  return a < b || (a == b && id < thanId);
}

// The 64-bit key (IDs below 2^32). An empty pixel holds kEmptyKey, above every sample's key.
constexpr uint64_t kEmptyKey = ~uint64_t(0);
inline uint64_t narrowKey(float depth, uint64_t id) {
  return uint64_t(depthBits(depth)) << 32 | (id & 0xffffffffu);
}

// The 128-bit key: compared as (hi, lo). An empty pixel holds kEmptyWideKey.
struct alignas(16) WideKey {
  uint64_t lo, hi;  // lo: the ID; hi: the depth bits (little-endian 128-bit layout)
  friend bool operator<(const WideKey& a, const WideKey& b) {
    return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
  }
};
constexpr WideKey kEmptyWideKey{~uint64_t(0), ~uint64_t(0)};
inline WideKey wideKey(float depth, uint64_t id) { return {id, depthBits(depth)}; }

// *p = min(*p, key), atomically (any number of threads at once).
inline void atomicMinKey(uint64_t* p, uint64_t key) {
  std::atomic_ref<uint64_t> a(*p);
  uint64_t cur = a.load(std::memory_order_relaxed);
  while (key < cur && !a.compare_exchange_weak(cur, key, std::memory_order_relaxed)) {
  }
}

// The same for a wide key, by a 16-byte compare-and-swap (x86-64: cmpxchg16b, inlined because the
// project compiles with -mcx16). Check wideKeysSupported() before use.
inline void atomicMinKey(WideKey* p, WideKey key) {
  __extension__ typedef unsigned __int128 U128;
  // Read hi before lo (x86 keeps loads in order): a torn read then never looks smaller than a
  // value the pixel really held, so skipping the write on it is safe.
  WideKey cur{0, __atomic_load_n(&p->hi, __ATOMIC_ACQUIRE)};
  cur.lo = __atomic_load_n(&p->lo, __ATOMIC_ACQUIRE);
  while (key < cur) {
    const U128 expected = U128(cur.hi) << 64 | cur.lo, desired = U128(key.hi) << 64 | key.lo;
    const U128 seen = __sync_val_compare_and_swap(reinterpret_cast<U128*>(p), expected, desired);
    if (seen == expected) return;
    cur = {uint64_t(seen), uint64_t(seen >> 64)};
  }
}

// Whether this CPU has the 16-byte compare-and-swap of wide keys.
bool wideKeysSupported();

// A frame of keys: every pass and thread puts samples by atomic minimum, then resolve() writes
// depth and ID into a framebuffer. Narrow unless the scene has 2^32 or more expanded triangles.
class KeyBuffer {
 public:
  // Sizes and clears to empty. Throws std::runtime_error for wide keys on a CPU without them.
  void reset(int width, int height, bool wide, int threads);
  int width() const { return width_; }
  int height() const { return height_; }
  bool wide() const { return wide_; }
  uint64_t* narrow() { return narrow_.data(); }
  WideKey* wideKeys() { return wide_keys_.data(); }
  // One sample at pixel index i.
  void put(size_t i, float depth, uint64_t id) {
    if (wide_)
      atomicMinKey(&wide_keys_[i], wideKey(depth, id));
    else
      atomicMinKey(&narrow_[i], narrowKey(depth, id));
  }
  // Depth and ID of every pixel into fb (colour untouched); empty pixels get +inf and kNoId.
  void resolve(Framebuffer& fb, int threads) const;

 private:
  int width_ = 0, height_ = 0;
  bool wide_ = false;
  std::vector<uint64_t> narrow_;
  std::vector<WideKey> wide_keys_;
};

}  // namespace lzb
