#include "mpi/composite.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <memory>
#include <vector>

#include "mpi/decomposition.hpp"
#include "mpi/frame_tiles.hpp"
#include "src/core/depth_key.hpp"
#include "src/core/error.hpp"
#include "src/core/prefetch.hpp"
#include "src/core/timer.hpp"

namespace lzb::mpi {

CompositeStrategy parseCompositeStrategy(const std::string& text, const std::string& field) {
  if (text == "reduce") return CompositeStrategy::kReduce;
  if (text == "bswap") return CompositeStrategy::kBinarySwap;
  if (text == "direct") return CompositeStrategy::kDirect;
  if (text == "tiles") return CompositeStrategy::kTiles;
  throw InputError(field + ": expected reduce, bswap, direct or tiles, got '" + text + "'");
}

std::string toString(CompositeStrategy s) {
  switch (s) {
    case CompositeStrategy::kReduce: return "reduce";
    case CompositeStrategy::kBinarySwap: return "bswap";
    case CompositeStrategy::kDirect: return "direct";
    case CompositeStrategy::kTiles: return "tiles";
  }
  return "?";
}

namespace {

// MPI counts are int: messages go in chunks of this many keys.
constexpr size_t kChunk = size_t(1) << 24;

struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels [x0, x1) x [y0, y1)
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  size_t area() const { return empty() ? 0 : size_t(x1 - x0) * size_t(y1 - y0); }
  Rect intersect(const Rect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  }
};

Rect rectAt(const std::vector<int>& v, size_t r) {
  return {v[4 * r], v[4 * r + 1], v[4 * r + 2], v[4 * r + 3]};
}

void setRect(std::vector<int>& v, size_t r, const Rect& x) {
  v[4 * r] = x.x0, v[4 * r + 1] = x.y0, v[4 * r + 2] = x.x1, v[4 * r + 3] = x.y1;
}

// A pixel carries information exactly when its depth is not kEmptyDepth (every writer leaves
// kEmptyDepth where it leaves kNoId, framebuffer.hpp): the touched pixels are found from the
// 4-byte depths, half the bytes of the IDs.
const uint32_t kEmptyBits = std::bit_cast<uint32_t>(kEmptyDepth);

const uint32_t* depthBits(const Framebuffer& fb, int y) {
  return reinterpret_cast<const uint32_t*>(fb.depth.data()) + size_t(y) * size_t(fb.width);
}

// The bounding rectangle of the covered pixels (empty when none is).
Rect touchedRect(const Framebuffer& fb) {
  int x0 = fb.width, y0 = fb.height, x1 = 0, y1 = 0;
#pragma omp parallel for schedule(static) reduction(min : x0, y0) reduction(max : x1, y1)
  for (int y = 0; y < fb.height; ++y) {
    const uint32_t* row = depthBits(fb, y);
    int first = 0;
    while (first < fb.width && row[first] == kEmptyBits) ++first;
    if (first == fb.width) continue;
    int last = fb.width - 1;
    while (row[last] == kEmptyBits) --last;
    x0 = std::min(x0, first), x1 = std::max(x1, last + 1);
    y0 = std::min(y0, y), y1 = std::max(y1, y + 1);
  }
  return {x0, y0, x1, y1};
}

Rect unionRect(const Group& g, const Rect& r) {
  int v[4] = {-r.x0, -r.y0, r.x1, r.y1}, u[4];
  LZB_MPI_CALL(MPI_Allreduce(v, u, 4, MPI_INT, MPI_MAX, g.comm));
  return {-u[0], -u[1], u[2], u[3]};
}

// Key types: the 64-bit key with MPI's own minimum, the 128-bit one with an operator of ours.
void wideMin(void* in, void* inout, int* len, MPI_Datatype*) {
  const WideKey* a = static_cast<const WideKey*>(in);
  WideKey* b = static_cast<WideKey*>(inout);
  for (int i = 0; i < *len; ++i)
    if (a[i] < b[i]) b[i] = a[i];
}

template <class K>
struct Keys;

template <>
struct Keys<uint64_t> {
  static uint64_t of(const Framebuffer& fb, size_t i) {
    return fb.id[i] == kNoId ? kEmptyKey : narrowKey(fb.depth[i], fb.id[i]);
  }
  static void put(Framebuffer& fb, size_t i, uint64_t k) {
    fb.depth[i] = k == kEmptyKey ? kEmptyDepth : std::bit_cast<float>(uint32_t(k >> 32));
    fb.id[i] = k == kEmptyKey ? kNoId : (k & 0xffffffffu);
  }
  static uint64_t min(uint64_t a, uint64_t b) { return std::min(a, b); }
  static constexpr uint64_t kEmpty = kEmptyKey;
  MPI_Datatype type = MPI_UINT64_T;
  MPI_Op op = MPI_MIN;
};

template <>
struct Keys<WideKey> {
  static WideKey of(const Framebuffer& fb, size_t i) {
    return fb.id[i] == kNoId ? kEmptyWideKey : wideKey(fb.depth[i], fb.id[i]);
  }
  static void put(Framebuffer& fb, size_t i, WideKey k) {
    const bool empty = k.hi == kEmptyWideKey.hi;
    fb.depth[i] = empty ? kEmptyDepth : std::bit_cast<float>(uint32_t(k.hi));
    fb.id[i] = empty ? kNoId : k.lo;
  }
  static WideKey min(WideKey a, WideKey b) { return b < a ? b : a; }
  static constexpr WideKey kEmpty = kEmptyWideKey;
  MPI_Datatype type;
  MPI_Op op;
  Keys() {
    LZB_MPI_CALL(MPI_Type_contiguous(2, MPI_UINT64_T, &type));
    LZB_MPI_CALL(MPI_Type_commit(&type));
    LZB_MPI_CALL(MPI_Op_create(&wideMin, /*commute=*/1, &op));
  }
  ~Keys() {
    MPI_Op_free(&op);
    MPI_Type_free(&type);
  }
};

// One pixel with its colour, as compositeWithColour sends it.
struct Pixel {
  float depth;
  Rgba8 color;
  uint64_t id;
};
static_assert(sizeof(Pixel) == 16);

// Whole pixels for the tiles' colour composite: merged in rank order, a higher rank's pixel
// replaces the lower ranks' only when strictly nearer (the reduce's tie rule, nearerPixel).
template <>
struct Keys<Pixel> {
  static Pixel of(const Framebuffer& fb, size_t i) { return {fb.depth[i], fb.color[i], fb.id[i]}; }
  static void put(Framebuffer& fb, size_t i, const Pixel& p) {
    fb.depth[i] = p.depth;
    fb.color[i] = p.color;
    fb.id[i] = p.id;
  }
  static Pixel min(const Pixel& lower, const Pixel& higher) {
    return nearer(higher.depth, higher.id, lower.depth, lower.id) ? higher : lower;
  }
};

// The keys of r, row by row.
template <class K>
void pack(const Framebuffer& fb, const Rect& r, K* out) {
  const int w = r.x1 - r.x0;
#pragma omp parallel for schedule(static)
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      out[size_t(y - r.y0) * size_t(w) + size_t(x - r.x0)] = Keys<K>::of(fb, fb.index(x, y));
}

template <class K>
void unpack(const K* in, const Rect& r, Framebuffer& fb) {
  const int w = r.x1 - r.x0;
#pragma omp parallel for schedule(static)
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x)
      Keys<K>::put(fb, fb.index(x, y), in[size_t(y - r.y0) * size_t(w) + size_t(x - r.x0)]);
}

// into = min(into, part) where part holds the keys of rect p and into those of rect r (p in r).
template <class K>
void mergeRect(K* into, const Rect& r, const K* part, const Rect& p) {
  const int w = r.x1 - r.x0, pw = p.x1 - p.x0;
#pragma omp parallel for schedule(static)
  for (int y = p.y0; y < p.y1; ++y) {
    K* dst = into + size_t(y - r.y0) * size_t(w) + size_t(p.x0 - r.x0);
    const K* src = part + size_t(y - p.y0) * size_t(pw);
    for (int x = 0; x < pw; ++x) dst[x] = Keys<K>::min(dst[x], src[x]);
  }
}

template <class K>
void sendKeys(const Group& g, const K* data, size_t n, int to, const Keys<K>& k) {
  for (size_t s = 0; s < n; s += kChunk)
    LZB_MPI_CALL(MPI_Send(data + s, int(std::min(kChunk, n - s)), k.type, to, 0, g.comm));
}

template <class K>
void receiveKeys(const Group& g, K* data, size_t n, int from, const Keys<K>& k) {
  for (size_t s = 0; s < n; s += kChunk)
    LZB_MPI_CALL(MPI_Recv(data + s, int(std::min(kChunk, n - s)), k.type, from, 0, g.comm,
                          MPI_STATUS_IGNORE));
}

// Gathers every rank's rows [rows[2r], rows[2r + 1]) of u's keys at the root and unpacks them.
template <class K>
void gatherRows(const Group& g, const std::vector<K>& keys, int rowBegin, int rowEnd, const Rect& u,
                Framebuffer& fb, const Keys<K>& k, double& bytes) {
  const size_t w = size_t(u.x1 - u.x0);
  int mine[2] = {rowBegin, rowEnd};
  std::vector<int> rows(g.root() ? 2 * size_t(g.size) : 0);
  LZB_MPI_CALL(MPI_Gather(mine, 2, MPI_INT, rows.data(), 2, MPI_INT, 0, g.comm));
  std::vector<int> counts, displs;
  std::vector<K> all;
  if (g.root()) {
    all.assign(u.area(), Keys<K>::kEmpty);
    for (int r = 0; r < g.size; ++r) {
      counts.push_back(int(size_t(rows[2 * r + 1] - rows[2 * r]) * w));
      displs.push_back(int(size_t(rows[2 * r]) * w));
    }
  }
  const int count = int(size_t(rowEnd - rowBegin) * w);
  LZB_MPI_CALL(MPI_Gatherv(keys.data() + size_t(rowBegin) * w, count, k.type, all.data(),
                           counts.data(), displs.data(), k.type, 0, g.comm));
  if (g.root()) unpack(all.data(), u, fb);
  else bytes += double(count) * sizeof(K);
}

template <class K>
double reduce(const Group& g, Framebuffer& fb, const Rect& u) {
  const Keys<K> k;
  const size_t n = u.area();
  std::vector<K> mine(n), result(g.root() ? n : 0);
  pack(fb, u, mine.data());
  for (size_t s = 0; s < n; s += kChunk)
    LZB_MPI_CALL(MPI_Reduce(mine.data() + s, g.root() ? result.data() + s : nullptr,
                            int(std::min(kChunk, n - s)), k.type, k.op, 0, g.comm));
  if (g.root()) unpack(result.data(), u, fb);
  return g.root() ? 0.0 : double(n) * sizeof(K);
}

template <class K>
double binarySwap(const Group& g, Framebuffer& fb, const Rect& u) {
  const Keys<K> k;
  const int height = u.y1 - u.y0;
  const size_t w = size_t(u.x1 - u.x0);
  std::vector<K> keys(u.area());
  pack(fb, u, keys.data());
  int pow2 = 1;
  while (pow2 * 2 <= g.size) pow2 *= 2;
  double bytes = 0.0;
  int a = 0, b = height;  // u's rows this rank holds
  if (g.rank >= pow2) {   // fold into the power of two
    sendKeys(g, keys.data(), keys.size(), g.rank - pow2, k);
    bytes += double(keys.size()) * sizeof(K);
    a = b = 0;
  } else if (g.rank + pow2 < g.size) {
    std::vector<K> other(keys.size());
    receiveKeys(g, other.data(), other.size(), g.rank + pow2, k);
    mergeRect(keys.data(), u, other.data(), u);
  }
  if (g.rank < pow2) {
    std::vector<K> incoming;
    for (int bit = 1; bit < pow2; bit <<= 1) {
      const int partner = g.rank ^ bit, mid = a + (b - a) / 2;
      const bool lower = (g.rank & bit) == 0;
      const int keepA = lower ? a : mid, keepB = lower ? mid : b;
      const int sendA = lower ? mid : a, sendB = lower ? b : mid;
      const size_t sendN = size_t(sendB - sendA) * w, keepN = size_t(keepB - keepA) * w;
      incoming.resize(keepN);
      LZB_MPI_CALL(MPI_Sendrecv(keys.data() + size_t(sendA) * w, int(sendN), k.type, partner, 1,
                                incoming.data(), int(keepN), k.type, partner, 1, g.comm,
                                MPI_STATUS_IGNORE));
      bytes += double(sendN) * sizeof(K);
      const Rect keep{u.x0, u.y0 + keepA, u.x1, u.y0 + keepB};
      mergeRect(keys.data() + size_t(keepA) * w, keep, incoming.data(), keep);
      a = keepA, b = keepB;
    }
  }
  gatherRows(g, keys, a, b, u, fb, k, bytes);
  return bytes;
}

template <class K>
double directSend(const Group& g, Framebuffer& fb, const Rect& u, const Rect& touched) {
  const Keys<K> k;
  const int P = g.size, height = u.y1 - u.y0;
  auto stripe = [&](int r) {
    return Rect{u.x0, u.y0 + int(int64_t(height) * r / P), u.x1, u.y0 + int(int64_t(height) * (r + 1) / P)};
  };
  // What this rank sends each stripe's owner: its touched rectangle's part of the stripe.
  const size_t ranks = static_cast<size_t>(P);
  std::vector<int> sendRects(4 * ranks), recvRects(4 * ranks);
  std::vector<int> sendCounts(ranks), sendDispls(ranks), recvCounts(ranks), recvDispls(ranks);
  std::vector<K> send;
  for (int r = 0; r < P; ++r) {
    Rect part = touched.intersect(stripe(r));
    if (part.empty()) part = {};
    setRect(sendRects, size_t(r), part);
    sendDispls[size_t(r)] = int(send.size());
    sendCounts[size_t(r)] = int(part.area());
    send.resize(send.size() + part.area());
    if (!part.empty()) pack(fb, part, send.data() + sendDispls[size_t(r)]);
  }
  LZB_MPI_CALL(MPI_Alltoall(sendRects.data(), 4, MPI_INT, recvRects.data(), 4, MPI_INT, g.comm));
  size_t total = 0;
  for (int r = 0; r < P; ++r) {
    const Rect p = rectAt(recvRects, size_t(r));
    recvDispls[size_t(r)] = int(total);
    recvCounts[size_t(r)] = int(p.area());
    total += p.area();
  }
  std::vector<K> recv(total);
  LZB_MPI_CALL(MPI_Alltoallv(send.data(), sendCounts.data(), sendDispls.data(), k.type, recv.data(),
                             recvCounts.data(), recvDispls.data(), k.type, g.comm));
  double bytes = 0.0;
  for (int r = 0; r < P; ++r)
    if (r != g.rank) bytes += double(sendCounts[size_t(r)]) * sizeof(K);
  // Reduce this rank's stripe, in the rows of u.
  const Rect mine = stripe(g.rank);
  std::vector<K> keys(u.area(), Keys<K>::kEmpty);
  for (int r = 0; r < P; ++r) {
    const Rect p = rectAt(recvRects, size_t(r));
    if (!p.empty()) mergeRect(keys.data(), u, recv.data() + recvDispls[size_t(r)], p);
  }
  gatherRows(g, keys, mine.y0 - u.y0, mine.y1 - u.y0, u, fb, k, bytes);
  return bytes;
}

}  // namespace

namespace {

// The tiles composite's byte buffers, kept between frames: a fresh 20 MB buffer a frame, zeroed
// and faulted in page by page, cost milliseconds on a dense 1080p frame.
struct TileBuffers {
  std::unique_ptr<char[]> send, receive;
  size_t sendSize = 0, receiveSize = 0;
  static char* fit(std::unique_ptr<char[]>& b, size_t& size, size_t need) {
    if (need > size) b.reset(new char[need]), size = need;  // uninitialised: every byte is written
    return b.get();
  }
};
TileBuffers& tileBuffers() {
  static TileBuffers buffers;  // only the main thread composites (mpi/README.md)
  return buffers;
}

// A row of n pixels of a tile as the tiles composite sends it (rowBytes(n) bytes at p, p 8-byte
// aligned): the keys one after the other; whole pixels as their n depths, n colours, n IDs, so
// that packing is three copies and merging reads contiguous arrays.
template <class K>
struct TileRows {
  static size_t rowBytes(int n) { return size_t(n) * sizeof(K); }
  static void pack(const Framebuffer& fb, size_t i, int n, char* p) {
    for (int k = 0; k < n; ++k, p += sizeof(K)) {
      const K key = Keys<K>::of(fb, i + size_t(k));
      std::memcpy(p, &key, sizeof(K));
    }
  }
  static void merge(Framebuffer& fb, size_t i, int n, const char* p) {
    for (int k = 0; k < n; ++k, p += sizeof(K)) {
      K key;
      std::memcpy(&key, p, sizeof(K));
      Keys<K>::put(fb, i + size_t(k), Keys<K>::min(Keys<K>::of(fb, i + size_t(k)), key));
    }
  }
};

// Whole pixels with their IDs as Id: uint64_t, or uint32_t where every ID of the scene is below
// 2^32 - 1 (kNoId truncates to 2^32 - 1 and is restored from it): 12 bytes a pixel instead of 16.
template <class Id>
struct PixelRows {
  static size_t rowBytes(int n) { return size_t(n) * (8 + sizeof(Id)); }
  static void pack(const Framebuffer& fb, size_t i, int n, char* p) {
    std::memcpy(p, &fb.depth[i], size_t(n) * 4);
    std::memcpy(p + 4 * n, &fb.color[i], size_t(n) * 4);
    if constexpr (sizeof(Id) == 8) {
      std::memcpy(p + 8 * n, &fb.id[i], size_t(n) * 8);
    } else {
      Id id[ScreenTiles::kDefaultSide];
      for (int k = 0; k < n; ++k) id[k] = Id(fb.id[i + size_t(k)]);
      std::memcpy(p + 8 * n, id, size_t(n) * sizeof(Id));
    }
  }
  // A higher rank's pixel replaces the lower ranks' only when strictly nearer (Keys<Pixel>::min).
  static void merge(Framebuffer& fb, size_t i, int n, const char* p) {
    float depth[ScreenTiles::kDefaultSide];
    Rgba8 color[ScreenTiles::kDefaultSide];
    Id id[ScreenTiles::kDefaultSide];
    std::memcpy(depth, p, size_t(n) * 4);
    std::memcpy(color, p + 4 * n, size_t(n) * 4);
    std::memcpy(id, p + 8 * n, size_t(n) * sizeof(Id));
    for (int k = 0; k < n; ++k) {
      const size_t j = i + size_t(k);
      const uint64_t full = id[k] == Id(kNoId) ? kNoId : uint64_t(id[k]);
      if (!nearer(depth[k], full, fb.depth[j], fb.id[j])) continue;
      fb.depth[j] = depth[k], fb.color[j] = color[k], fb.id[j] = full;
    }
  }
};
struct NarrowPixel;  // the 12-byte pixel's tag
template <>
struct TileRows<Pixel> : PixelRows<uint64_t> {};
template <>
struct TileRows<NarrowPixel> : PixelRows<uint32_t> {};

// The cache lines of a tile's depths, colours and IDs in fb, fetched ahead of packing or merging
// it: tiles lie 7.5 KB rows apart in a 1080p frame, out of the hardware prefetcher's reach.
void prefetchTile(const Framebuffer& fb, const TileRect& r) {
  for (int y = r.y0; y < r.y1; ++y) {
    const size_t i = fb.index(r.x0, y), last = fb.index(r.x1 - 1, y);
    prefetchRead(&fb.depth[i]), prefetchRead(&fb.depth[last]);
    prefetchRead(&fb.color[i]), prefetchRead(&fb.color[last]);
    for (size_t j = i; j <= last; j += 8) prefetchRead(&fb.id[j]);
    prefetchRead(&fb.id[last]);
  }
}

// A tile as sent: its index (8 bytes, keeping the rows aligned), then its rows.
size_t tileBytes(const TileRect& r, size_t (*rowBytes)(int)) {
  return sizeof(int64_t) + size_t(r.y1 - r.y0) * rowBytes(r.x1 - r.x0);
}

// The tiles composite's messages: a rank's touched tiles go to the root in chunks of
// kTilesPerChunk, then an empty message ends them, so that the root merges a chunk while the rank
// packs the next. One tag on the group's communicator (no other message is matched).
constexpr int kTilesTag = 2;
constexpr size_t kTilesPerChunk = 32;

// Packs tiles [begin, end) of `list` to out + at[begin], in parallel over the tiles.
template <class K>
void packTiles(const Framebuffer& fb, const ScreenTiles& tiles, const std::vector<int>& list,
               const std::vector<size_t>& at, size_t begin, size_t end, char* out) {
#pragma omp parallel for schedule(static)
  for (size_t k = begin; k < end; ++k) {
    if (k + 1 < end) prefetchTile(fb, tiles.tile(list[k + 1]));
    const TileRect r = tiles.tile(list[k]);
    char* p = out + at[k];
    const int64_t index = list[k];
    std::memcpy(p, &index, sizeof(index));
    p += sizeof(index);
    for (int y = r.y0; y < r.y1; ++y, p += TileRows<K>::rowBytes(r.x1 - r.x0))
      TileRows<K>::pack(fb, fb.index(r.x0, y), r.x1 - r.x0, p);
  }
}

// A non-root rank's side: its touched tiles packed and sent chunk by chunk; returns the bytes.
template <class K>
size_t sendTiles(const Group& g, const Framebuffer& fb, const ScreenTiles& tiles,
                 const std::vector<uint8_t>& touched) {
  const std::vector<int> list = markedTiles(touched);
  std::vector<size_t> at(list.size() + 1, 0);
  for (size_t k = 0; k < list.size(); ++k)
    at[k + 1] = at[k] + tileBytes(tiles.tile(list[k]), &TileRows<K>::rowBytes);
  TileBuffers& b = tileBuffers();
  char* out = TileBuffers::fit(b.send, b.sendSize, at.back());
  std::vector<MPI_Request> sends(1);
  for (size_t begin = 0; begin < list.size(); begin += kTilesPerChunk) {
    const size_t end = std::min(list.size(), begin + kTilesPerChunk);
    packTiles<K>(fb, tiles, list, at, begin, end, out);
    sends.emplace_back();
    LZB_MPI_CALL(MPI_Isend(out + at[begin], int(at[end] - at[begin]), MPI_BYTE, 0, kTilesTag,
                           g.comm, &sends.back()));
  }
  LZB_MPI_CALL(MPI_Isend(nullptr, 0, MPI_BYTE, 0, kTilesTag, g.comm, &sends.front()));  // the end
  LZB_MPI_CALL(MPI_Waitall(int(sends.size()), sends.data(), MPI_STATUSES_IGNORE));
  return at.back();
}

// Packed tiles [0, bytes) of `in` into the root's frame, the nearer pixel kept, in parallel over
// the tiles (a rank sends each tile once); marks them in `touched`.
template <class K>
void mergeTiles(const char* in, size_t bytes, const ScreenTiles& tiles, Framebuffer& fb,
                std::vector<uint8_t>& touched) {
  std::vector<std::pair<int, size_t>> sent;  // tile, where its rows start
  for (size_t at = 0; at < bytes;) {
    int64_t t;
    std::memcpy(&t, in + at, sizeof(t));
    sent.emplace_back(int(t), at + sizeof(t));
    touched[size_t(t)] = 1;
    at += tileBytes(tiles.tile(int(t)), &TileRows<K>::rowBytes);
  }
#pragma omp parallel for schedule(static)
  for (size_t k = 0; k < sent.size(); ++k) {
    if (k + 1 < sent.size()) prefetchTile(fb, tiles.tile(sent[k + 1].first));
    const TileRect r = tiles.tile(sent[k].first);
    const char* p = in + sent[k].second;
    for (int y = r.y0; y < r.y1; ++y, p += TileRows<K>::rowBytes(r.x1 - r.x0))
      TileRows<K>::merge(fb, fb.index(r.x0, y), r.x1 - r.x0, p);
  }
}

// The root's side: every rank's chunks merged as they come, ranks in order (on equal keys the
// lower rank's pixel stays).
template <class K>
void receiveTiles(const Group& g, Framebuffer& fb, const ScreenTiles& tiles,
                  std::vector<uint8_t>& touched) {
  TileBuffers& b = tileBuffers();
  for (int r = 1; r < g.size; ++r) {
    for (int bytes = 1; bytes > 0;) {  // until the empty message
      MPI_Status status;
      LZB_MPI_CALL(MPI_Probe(r, kTilesTag, g.comm, &status));
      LZB_MPI_CALL(MPI_Get_count(&status, MPI_BYTE, &bytes));
      char* in = TileBuffers::fit(b.receive, b.receiveSize, size_t(bytes));
      LZB_MPI_CALL(MPI_Recv(in, bytes, MPI_BYTE, r, kTilesTag, g.comm, MPI_STATUS_IGNORE));
      mergeTiles<K>(in, size_t(bytes), tiles, fb, touched);
    }
  }
}

template <class K>
double tileSend(const Group& g, Framebuffer& fb, std::vector<uint8_t>& touched) {
  const ScreenTiles tiles(fb.width, fb.height);
  if (!g.root()) return double(sendTiles<K>(g, fb, tiles, touched));
  receiveTiles<K>(g, fb, tiles, touched);
  return 0.0;
}

template <class K>
double composite(const Group& g, Framebuffer& fb, CompositeStrategy s) {
  if (s == CompositeStrategy::kTiles) {
    std::vector<uint8_t> touched = touchedTiles(fb, ScreenTiles(fb.width, fb.height));
    return tileSend<K>(g, fb, touched);
  }
  const Rect touched = touchedRect(fb);
  const Rect u = unionRect(g, touched);
  if (u.empty()) return 0.0;  // nothing anywhere: the root's frame is already empty
  switch (s) {
    case CompositeStrategy::kReduce: return reduce<K>(g, fb, u);
    case CompositeStrategy::kBinarySwap: return binarySwap<K>(g, fb, u);
    default: return directSend<K>(g, fb, u, touched.empty() ? Rect{} : touched);
  }
}

// in is the lower ranks' side (the operator is declared non-commutative, so MPI applies it in
// rank order): on equal (depth, id) the lower rank's pixel stays. Colour is not in the key, and
// an empty pixel may carry colour (rzb's Gaussian reconstruction spreads it past the geometry),
// so only a fixed preference gives the 1-rank image.
void nearerPixel(void* in, void* inout, int* len, MPI_Datatype*) {
  const Pixel* a = static_cast<const Pixel*>(in);
  Pixel* b = static_cast<Pixel*>(inout);
  for (int i = 0; i < *len; ++i)
    if (!nearer(b[i].depth, b[i].id, a[i].depth, a[i].id)) b[i] = a[i];
}

}  // namespace

CompositeStats compositeAtRoot(const Group& g, Framebuffer& fb, CompositeStrategy strategy,
                               bool wide) {
  CompositeStats stats;
  if (g.size == 1) return stats;
  Stopwatch clock;
  stats.bytesSent = wide ? composite<WideKey>(g, fb, strategy) : composite<uint64_t>(g, fb, strategy);
  stats.seconds = clock.seconds();
  return stats;
}

CompositeStats compositeWithColour(const Group& g, Framebuffer& fb, CompositeStrategy strategy,
                                   std::vector<uint8_t>& touched, bool wide) {
  CompositeStats stats;
  if (g.size == 1) return stats;
  Stopwatch clock;
  if (strategy == CompositeStrategy::kTiles) {
    stats.bytesSent =
        wide ? tileSend<Pixel>(g, fb, touched) : tileSend<NarrowPixel>(g, fb, touched);
    stats.seconds = clock.seconds();
    return stats;
  }
  const size_t n = fb.size();
  std::vector<Pixel> mine(n), result(g.root() ? n : 0);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) mine[i] = Pixel{fb.depth[i], fb.color[i], fb.id[i]};
  MPI_Datatype type;
  LZB_MPI_CALL(MPI_Type_contiguous(sizeof(Pixel), MPI_BYTE, &type));
  LZB_MPI_CALL(MPI_Type_commit(&type));
  MPI_Op op;
  LZB_MPI_CALL(MPI_Op_create(&nearerPixel, /*commute=*/0, &op));
  for (size_t start = 0; start < n; start += kChunk) {
    const int count = int(std::min(kChunk, n - start));
    LZB_MPI_CALL(MPI_Reduce(mine.data() + start, g.root() ? result.data() + start : nullptr, count,
                            type, op, 0, g.comm));
  }
  MPI_Op_free(&op);
  MPI_Type_free(&type);
  if (g.root()) {
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
      fb.depth[i] = result[i].depth;
      fb.color[i] = result[i].color;
      fb.id[i] = result[i].id;
    }
  } else {
    stats.bytesSent = double(n * sizeof(Pixel));
  }
  stats.seconds = clock.seconds();
  return stats;
}

}  // namespace lzb::mpi
