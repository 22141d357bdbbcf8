#include "src/sampletree/external_build.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <optional>
#include <queue>
#include <unordered_map>
#include <vector>

#include "src/core/atomic_file.hpp"
#include "src/core/error.hpp"
#include "src/core/progress.hpp"
#include "src/core/timer.hpp"
#include "src/sampletree/cell_census.hpp"
#include "src/sampletree/sample_draw.hpp"
#include "src/sampletree/scratch_file.hpp"
#include "src/sampletree/spill_file.hpp"
#include "src/sampletree/store_writer.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_layout.hpp"
#include "src/sampletree/tree_store.hpp"

namespace lzb::sampletree {

namespace {

// The input with a progress line per pass.
class PassStream : public TriangleStream {
 public:
  PassStream(const TriangleStream& in, bool progress, ExternalReport& report)
      : in_(in), progress_(progress), report_(report) {}
  const std::string& where() const override { return in_.where(); }
  uint64_t expected() const override { return in_.expected(); }
  SceneOutline outline() const override { return in_.outline(); }
  void forEach(const TriangleSink& sink) const override {
    const int pass = ++report_.streamPasses;
    const Stopwatch clock;
    Progress line("build-tree: input pass " + std::to_string(pass), in_.expected(), progress_);
    in_.forEach([&](std::span<const StreamTriangle> batch) {
      sink(batch);
      line.add(batch.size());
    });
    report_.inputSeconds += clock.seconds();
  }

 private:
  const TriangleStream& in_;
  bool progress_;
  ExternalReport& report_;
};

// The scratch folder, removed with everything in it when the build ends (or fails).
struct ScratchFolder {
  std::filesystem::path path;
  explicit ScratchFolder(const std::filesystem::path& parent)
      : path(parent / (".lzb-build-tree-" + std::to_string(::getpid()))) {
    std::filesystem::create_directory(path);  // not its parents: a missing folder is an error
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

// Cells classified by the census, in preorder (children in octant order).
struct Plan {
  std::vector<CellKey> buckets;
  std::unordered_map<CellKey, uint32_t, CellKeyHash> bucketOf, topOf;
  size_t tops = 0;
};

void classify(const CellCensus& census, const CellKey& key, Plan& plan) {
  if (!census.top(key)) {
    plan.bucketOf.emplace(key, uint32_t(plan.buckets.size()));
    plan.buckets.push_back(key);
    return;
  }
  plan.topOf.emplace(key, uint32_t(plan.tops++));
  for (int o = 0; o < 8; ++o)
    if (census.find(key.child(o))) classify(census, key.child(o), plan);
}

// A bucket after its build: its root as the top levels see it (its triangles moved to the top
// input), and where its nodes below the root lie in the scratch arrays.
struct BucketResult {
  BuildNode root;
  HiddenSubtree below;
  uint64_t nodesAt = 0, positionsAt = 0, idsAt = 0, coloursAt = 0;  // byte offsets
};

struct ScratchArrays {
  ScratchFile nodes, positions, ids, colours;
  explicit ScratchArrays(const std::filesystem::path& dir)
      : nodes(dir / "nodes"), positions(dir / "positions"), ids(dir / "ids"),
        colours(dir / "colours") {}
};

template <class T>
uint64_t reserveFor(ScratchFile& f, const std::vector<T>& v) {
  return f.reserve(v.size() * sizeof(T));
}

template <class T>
void writeVector(const ScratchFile& f, uint64_t at, const std::vector<T>& v) {
  f.write(at, v.data(), v.size() * sizeof(T));
}

TriangleInput toInput(const std::vector<StreamTriangle>& tris) {
  TriangleInput in;
  in.positions.reserve(3 * tris.size());
  in.ids.reserve(tris.size());
  in.colours.reserve(tris.size());
  for (const StreamTriangle& t : tris) in.add(t);
  return in;
}

std::vector<double> areasOf(const TriangleInput& in) {
  std::vector<double> areas(in.size());
  for (size_t t = 0; t < in.size(); ++t) areas[t] = in.area(t);
  return areas;
}

void requireTopFits(uint64_t triangles, uint64_t limit) {
  require(triangles <= limit, "--mem-mb",
          "the top levels (cells above the buckets) hold more than the " + std::to_string(limit) +
              " triangles the budget gives them: raise it");
}

// One bucket built as the in-memory build builds that cell: the nodes below its root laid out,
// and its root with the triangles left in it (indices into rootTriangles).
struct BuiltBucket {
  SampleTree below;
  BuildNode root;
  TriangleInput rootTriangles;
};

BuiltBucket buildBucket(const CellKey& key, const std::vector<StreamTriangle>& tris,
                        const CellOctree& frame, const TreeParams& params, int threads) {
  const TriangleInput in = toInput(tris);
  const std::vector<double> areas = areasOf(in);
  CellOctree oct;
  oct.origin = frame.origin;
  oct.size = frame.size;
  buildCellSubtree(oct, in, areas, params.leafTriangles, key.level, key.cell);
  drawSamples(oct, areas, params.c, params.seed, threads);
  BuiltBucket b;
  TreeLayout(oct, in, areas).emitChildren(0, b.below);
  b.root = oct.nodes[0];
  b.root.child.fill(kNoChild);
  b.root.own.clear();
  for (uint32_t t : oct.nodes[0].own) {
    b.root.own.push_back(uint32_t(b.rootTriangles.size()));
    b.rootTriangles.addFrom(in, t);
  }
  return b;
}

// Places a built bucket in the scratch arrays (the room set aside, in bucket order) and appends
// its root's triangles to the top levels' input.
BucketResult placeBucket(BuiltBucket& b, TriangleInput& top, ScratchArrays& scratch) {
  BucketResult r;
  r.below = {b.below.nodes.size(), b.below.ids.size()};
  r.nodesAt = reserveFor(scratch.nodes, b.below.nodes);
  r.positionsAt = reserveFor(scratch.positions, b.below.positions);
  r.idsAt = reserveFor(scratch.ids, b.below.ids);
  r.coloursAt = reserveFor(scratch.colours, b.below.colours);
  r.root = std::move(b.root);
  for (uint32_t& t : r.root.own) {
    top.addFrom(b.rootTriangles, t);
    t = uint32_t(top.size() - 1);
  }
  return r;
}

// Writes a placed bucket's arrays where placeBucket set room aside (any thread).
void writeBucket(const SampleTree& below, const BucketResult& at, const ScratchArrays& scratch) {
  writeVector(scratch.nodes, at.nodesAt, below.nodes);
  writeVector(scratch.positions, at.positionsAt, below.positions);
  writeVector(scratch.ids, at.idsAt, below.ids);
  writeVector(scratch.colours, at.coloursAt, below.colours);
}

// The buckets' triangles in the spill: each bucket one or more of its partitions (a partition per
// bucket from a writing pass; from the last counting pass, one per cell where triangles stopped).
struct BucketReader {
  const SpillFile& spill;
  std::vector<std::vector<uint32_t>> parts;  // per bucket

  uint64_t count(uint32_t b) const {
    uint64_t n = 0;
    for (uint32_t p : parts[b]) n += spill.count(p);
    return n;
  }
  // The bucket's triangles in input order: its partitions merged by ID (the stream's order).
  std::vector<StreamTriangle> read(uint32_t b) const {
    if (parts[b].size() == 1) return spill.read(parts[b][0]);
    std::vector<std::vector<StreamTriangle>> runs;
    for (uint32_t p : parts[b]) runs.push_back(spill.read(p));
    return mergeById(runs, count(b));
  }
  static std::vector<StreamTriangle> mergeById(const std::vector<std::vector<StreamTriangle>>& runs,
                                               uint64_t total);
};

// A k-way merge that copies a run's triangles up to the next run's head at once (a run holds a
// cell's triangles, mostly whole objects in a row).
std::vector<StreamTriangle> BucketReader::mergeById(
    const std::vector<std::vector<StreamTriangle>>& runs, uint64_t total) {
  using Head = std::pair<uint64_t, size_t>;  // (ID, run)
  std::priority_queue<Head, std::vector<Head>, std::greater<>> heads;
  std::vector<size_t> at(runs.size(), 0);
  for (size_t r = 0; r < runs.size(); ++r)
    if (!runs[r].empty()) heads.emplace(runs[r][0].id, r);
  std::vector<StreamTriangle> out;
  out.reserve(size_t(total));
  while (!heads.empty()) {
    const size_t r = heads.top().second;
    heads.pop();
    const uint64_t next = heads.empty() ? UINT64_MAX : heads.top().first;
    const std::vector<StreamTriangle>& run = runs[r];
    size_t& k = at[r];
    do out.push_back(run[k++]);
    while (k < run.size() && run[k].id < next);
    if (k < run.size()) heads.emplace(run[k].id, r);
  }
  return out;
}

// The counting passes' sink: each pass spills every triangle to the partition of the cell where
// it stopped, replacing the last pass's spill; the last pass's serves as the writing pass when the
// IDs came in increasing order (else bucket reads could not merge partitions back into order).
class PartitionSpill : public CensusSink {
 public:
  PartitionSpill(std::filesystem::path path, uint64_t bufferTriangles)
      : path_(std::move(path)), bufferTriangles_(bufferTriangles) {}
  void beginPass() override {
    spill_.reset();
    spill_.emplace(path_, 0, bufferTriangles_);
    partOf_.clear();
    keys_.clear();
    memo_ = {};
    ordered_ = true;
    lastId_.reset();
  }
  void add(const StreamTriangle& t, const CellKey& deepest) override {
    if (lastId_ && t.id <= *lastId_) ordered_ = false;
    lastId_ = t.id;
    spill_->add(memo_.get(deepest, [&](const CellKey& k) { return partition(k); }), t);
  }
  bool ordered() const { return ordered_; }
  void drop() { spill_.reset(); }
  SpillFile& spill() { return *spill_; }
  const std::vector<CellKey>& keys() const { return keys_; }  // per partition

 private:
  uint32_t partition(const CellKey& k) {
    const auto [it, fresh] = partOf_.try_emplace(k, uint32_t(keys_.size()));
    if (fresh) keys_.push_back(k);
    return it->second;
  }
  std::filesystem::path path_;
  uint64_t bufferTriangles_;
  std::optional<SpillFile> spill_;
  std::unordered_map<CellKey, uint32_t, CellKeyHash> partOf_;
  std::vector<CellKey> keys_;
  PathMemo<uint32_t> memo_;
  bool ordered_ = true;
  std::optional<uint64_t> lastId_;
};

// Builds the buckets on `threads` threads, one bucket each (a bucket's own sampling gains little
// from more), committing them in order: a thread takes the next bucket once its last is
// committed, so at most `threads` buckets are held and no thread waits for a whole group.
std::vector<BucketResult> buildBuckets(const Plan& plan, const BucketReader& spill,
                                       const CellOctree& frame, const TreeParams& params,
                                       int threads, const ExternalOptions& options,
                                       TriangleInput& top, ScratchArrays& scratch) {
  std::vector<BucketResult> results;
  uint64_t total = 0;
  for (uint32_t b = 0; b < plan.buckets.size(); ++b) total += spill.count(b);
  Progress progress("build-tree: buckets", total, options.progress);
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  const auto fail = [&](std::exception_ptr e) {
#pragma omp critical(lzb_bucket_error)
    if (!error) error = e;
    failed = true;
  };
  const int64_t n = int64_t(plan.buckets.size());
#pragma omp parallel for ordered schedule(dynamic, 1) num_threads(std::max(threads, 1))
  for (int64_t b = 0; b < n; ++b) {
    BuiltBucket built;
    std::exception_ptr mine;
    if (!failed) try {
        built = buildBucket(plan.buckets[size_t(b)], spill.read(uint32_t(b)), frame, params, 1);
        progress.add(spill.count(uint32_t(b)));
      } catch (...) {
        mine = std::current_exception();
      }
    BucketResult at;  // the offsets only: `results` may grow meanwhile
#pragma omp ordered
    if (!failed) try {
        if (mine) std::rethrow_exception(mine);
        results.push_back(placeBucket(built, top, scratch));
        at.nodesAt = results.back().nodesAt, at.positionsAt = results.back().positionsAt;
        at.idsAt = results.back().idsAt, at.coloursAt = results.back().coloursAt;
        requireTopFits(top.size(), options.topTriangles);
      } catch (...) {
        fail(std::current_exception());
      }
    // The writes overlap the next buckets' builds and placing.
    if (!failed) try {
        writeBucket(built.below, at, scratch);
      } catch (...) {
        fail(std::current_exception());
      }
  }
  if (error) std::rethrow_exception(error);
  return results;
}

// The top levels as an octree: top cells with the triangles that stay in them, and the buckets'
// roots as leaves (their subtrees hidden below them).
struct TopTree {
  CellOctree oct;
  std::vector<HiddenSubtree> hidden;
  std::vector<int64_t> bucketAt;  // per node: its bucket, or -1
};

int32_t addTopNode(const CellCensus& census, const Plan& plan, const CellKey& key,
                   const std::vector<BucketResult>& buckets,
                   const std::vector<std::vector<uint32_t>>& stays, TopTree& t) {
  const int32_t index = int32_t(t.oct.nodes.size());
  if (const auto b = plan.bucketOf.find(key); b != plan.bucketOf.end()) {
    t.oct.nodes.push_back(buckets[b->second].root);
    t.hidden.push_back(buckets[b->second].below);
    t.bucketAt.push_back(b->second);
    return index;
  }
  BuildNode n;
  std::copy(key.cell, key.cell + 3, n.cell);
  n.level = key.level;
  n.subtreeTriangles = census.find(key)->count;
  n.subtreeArea = census.find(key)->area;
  n.own = stays[plan.topOf.at(key)];
  t.oct.nodes.push_back(std::move(n));
  t.hidden.emplace_back();
  t.bucketAt.push_back(-1);
  for (int o = 0; o < 8; ++o)
    if (census.find(key.child(o))) {
      const int32_t c = addTopNode(census, plan, key.child(o), buckets, stays, t);
      t.oct.nodes[size_t(index)].child[size_t(o)] = c;
    }
  return index;
}

// Copies n elements of T from a scratch file at byte offset `at` to the store, in pieces,
// shifting nodes by `shift` when given.
template <class T, class Shift>
void copyScratch(const ScratchFile& f, uint64_t at, uint64_t n, StoreWriter& w, Shift&& shift) {
  constexpr uint64_t kPiece = 1 << 16;
  std::vector<T> piece;
  for (uint64_t done = 0; done < n; done += kPiece) {
    piece.resize(size_t(std::min(kPiece, n - done)));
    f.read(at + done * sizeof(T), piece.size() * sizeof(T), piece.data());
    for (T& x : piece) shift(x);
    w.append(piece.data(), piece.size() * sizeof(T));
  }
}

// Writes the store: the top levels' nodes and triangles with every bucket's spliced in where its
// root stands, section by section.
struct StoreAssembly {
  const SampleTree& head;  // the top levels laid out (buckets' roots included)
  const std::vector<std::pair<size_t, size_t>>& splices;  // (head node, top octree node)
  const TopTree& top;
  const std::vector<BucketResult>& buckets;
  const ScratchArrays& scratch;

  const BucketResult& spliced(size_t k) const {
    return buckets[size_t(top.bucketAt[splices[k].second])];
  }
  void nodes(StoreWriter& w) const {
    uint64_t hiddenBefore = 0;
    size_t next = 0;
    for (size_t k = 0; k < head.nodes.size(); ++k) {
      w.append(&head.nodes[k], sizeof(TreeNode));
      if (next == splices.size() || splices[next].first != k) continue;
      const BucketResult& b = spliced(next++);
      const uint64_t nodeBase = k + hiddenBefore + 1;
      const uint64_t triBase = head.nodes[k].firstTriangle + head.nodes[k].triangleCount;
      copyScratch<TreeNode>(scratch.nodes, b.nodesAt, b.below.nodes, w, [&](TreeNode& n) {
        n.firstTriangle += triBase;
        n.subtreeEnd = uint32_t(n.subtreeEnd + nodeBase);
      });
      hiddenBefore += b.below.nodes;
    }
  }
  // One triangle array: the head's part of each node, then the spliced bucket's.
  template <class T>
  void triangles(StoreWriter& w, const std::vector<T>& own, size_t perTriangle,
                 const ScratchFile& f, uint64_t BucketResult::*at) const {
    size_t cursor = 0, next = 0;
    for (size_t k = 0; k < head.nodes.size(); ++k) {
      const size_t n = size_t(head.nodes[k].triangleCount) * perTriangle;
      w.append(own.data() + cursor, n * sizeof(T));
      cursor += n;
      if (next == splices.size() || splices[next].first != k) continue;
      const BucketResult& b = spliced(next++);
      copyScratch<T>(f, b.*at, b.below.triangles * perTriangle, w, [](T&) {});
    }
  }
  void write(StoreWriter& w) const {
    nodes(w);
    triangles(w, head.positions, 3, scratch.positions, &BucketResult::positionsAt);
    triangles(w, head.ids, 1, scratch.ids, &BucketResult::idsAt);
    triangles(w, head.colours, 1, scratch.colours, &BucketResult::coloursAt);
  }
};

Bounds boundsPass(const TriangleStream& in, uint64_t& count) {
  Bounds b;
  count = 0;
  in.forEach([&](std::span<const StreamTriangle> batch) {
    for (const StreamTriangle& t : batch)
      for (const glm::vec3& v : t.v) b.extend(glm::dvec3(v));
    count += batch.size();
  });
  return b;
}

// The writing pass: each triangle to its bucket, or kept where it stays in a top cell.
std::vector<std::vector<StreamTriangle>> writingPass(const TriangleStream& in,
                                                     const CellOctree& frame,
                                                     const CellCensus& census, const Plan& plan,
                                                     SpillFile& spill, uint64_t limit) {
  std::vector<std::vector<StreamTriangle>> stays(plan.tops);
  uint64_t stayed = 0;
  // Per cell: its top cell's index, else its bucket's with kBucket set.
  constexpr uint64_t kBucket = uint64_t(1) << 32;
  const auto where = [&](const CellKey& k) {
    const auto top = plan.topOf.find(k);
    return top != plan.topOf.end() ? uint64_t(top->second) : kBucket | plan.bucketOf.at(k);
  };
  PathMemo<bool> tops;
  PathMemo<uint64_t> places;
  in.forEach([&](std::span<const StreamTriangle> batch) {
    for (const StreamTriangle& t : batch) {
      CellKey last;
      descend(t, frame, [&](const CellKey& k) {
        last = k;
        return tops.get(k, [&](const CellKey& key) { return census.top(key); });
      });
      const uint64_t place = places.get(last, where);
      if (place & kBucket) {
        spill.add(uint32_t(place), t);
      } else {
        stays[size_t(place)].push_back(t);
        requireTopFits(++stayed, limit);
      }
    }
  });
  spill.flush();
  return stays;
}

// The last counting pass's spill as the writing pass's result: each partition is part of a
// bucket (below the cell where its triangles stopped), or the triangles staying in a top cell.
std::vector<std::vector<StreamTriangle>> partitionsToBuckets(
    const CellCensus& census, const Plan& plan, PartitionSpill& partitions,
    std::vector<std::vector<uint32_t>>& parts, uint64_t limit) {
  SpillFile& spill = partitions.spill();
  spill.flush();
  parts.assign(plan.buckets.size(), {});
  std::vector<std::pair<uint32_t, uint32_t>> stayParts;  // (top cell, partition)
  uint64_t stayed = 0;
  for (uint32_t p = 0; p < partitions.keys().size(); ++p) {
    CellKey k = partitions.keys()[p];
    if (census.top(k)) {
      stayParts.emplace_back(plan.topOf.at(k), p);
      stayed += spill.count(p);
      continue;
    }
    while (k.level > 0 && !census.top(k.parent())) k = k.parent();
    parts[plan.bucketOf.at(k)].push_back(p);
  }
  requireTopFits(stayed, limit);
  std::vector<std::vector<StreamTriangle>> stays(plan.tops);
  for (const auto& [c, p] : stayParts) stays[c] = spill.read(p);
  return stays;
}

// The input as the passes read it: a generator is copied on the first pass and read back (it
// costs more to run than to read); the generator gets a thread of its own on the first pass, so
// it overlaps the copy's writes.
struct PassInput {
  ScratchFolder dir;
  ReadAheadStream generated;
  std::optional<CopiedStream> copied;
  std::optional<ReadAheadStream> ahead;
  std::optional<PassStream> in;

  PassInput(const TriangleStream& source, const ExternalOptions& options, ExternalReport& report)
      : dir(options.scratchDir), generated(source) {
    if (source.regenerates()) copied.emplace(generated, dir.path / "input");
    ahead.emplace(copied ? static_cast<const TriangleStream&>(*copied) : source);
    in.emplace(*ahead, options.progress, report);
  }
};

// One external build as it passes through its phases: bounds, counting (the census and the
// plan), buckets (spilled, then built), top levels and store.
class ExternalBuild {
 public:
  ExternalBuild(const TriangleStream& source, const TreeParams& params,
                const ExternalOptions& options, int threads)
      : params_(params), options_(options), threads_(threads), input_(source, options, report_) {}

  ExternalReport run(const std::string& out) {
    const Bounds bounds = readBounds();
    if (report_.triangles == 0) return writeEmpty(out);
    fitRootCube(frame_, bounds);
    countCells();
    buildBucketsFromSpill();
    writeStore(out);
    return report_;
  }

 private:
  const TriangleStream& in() const { return *input_.in; }

  Bounds readBounds() {
    const Bounds bounds = boundsPass(in(), report_.triangles);
    requireFloatResolves(bounds, in().where());
    return bounds;
  }

  // Nothing to split: the in-memory build's empty tree.
  ExternalReport writeEmpty(const std::string& out) {
    SampleTree empty;
    empty.params = params_;
    empty.outline = outlineText(in().outline());
    writeTree(empty, out);
    report_.storeBytes = storeBytes(empty);
    return report_;
  }

  // The counting passes (each spilling to the partitions) and the buckets they give.
  void countCells() {
    partitions_.emplace(input_.dir.path / "spill", options_.bufferTriangles);
    census_.emplace(in(), frame_, options_.bucketTriangles, &*partitions_);
    report_.countingPasses = report_.streamPasses - 1;
    classify(*census_, CellKey{}, plan_);
    for (const CellKey& k : plan_.buckets)
      report_.largestBucket = std::max(report_.largestBucket, census_->find(k)->count);
    require(report_.largestBucket <= options_.bucketTriangles, "--mem-mb",
            "a cell of the deepest level holds " + std::to_string(report_.largestBucket) +
                " triangles, more than a bucket may (" + std::to_string(options_.bucketTriangles) +
                "): raise it");
    report_.buckets = plan_.buckets.size();
    report_.topCells = plan_.tops;
  }

  // The buckets' triangles spilled (by the last counting pass, or a writing pass when its IDs
  // came out of order), each bucket built, and the triangles staying in top cells gathered.
  void buildBucketsFromSpill() {
    scratch_.emplace(input_.dir.path);
    stayIndex_.assign(plan_.tops, {});
    // a writing pass's spill, when the last counting pass's is not usable
    std::optional<SpillFile> written;
    std::vector<std::vector<uint32_t>> parts;
    std::vector<std::vector<StreamTriangle>> stays;
    if (partitions_->ordered()) {
      stays = partitionsToBuckets(*census_, plan_, *partitions_, parts, options_.topTriangles);
    } else {
      partitions_->drop();
      written.emplace(input_.dir.path / "spill-written", plan_.buckets.size(),
                      options_.bufferTriangles);
      stays = writingPass(in(), frame_, *census_, plan_, *written, options_.topTriangles);
      for (uint32_t b = 0; b < plan_.buckets.size(); ++b) parts.push_back({b});
    }
    if (input_.copied) input_.copied->drop();  // the last pass
    const BucketReader spill{written ? *written : partitions_->spill(), std::move(parts)};
    report_.spillBytes = spill.spill.bytesWritten();
    const Stopwatch clock;
    buckets_ =
        buildBuckets(plan_, spill, frame_, params_, threads_, options_, topInput_, *scratch_);
    report_.bucketSeconds = clock.seconds();
    partitions_->drop();  // the spill goes before the store is written, as the writing pass's did
    for (size_t c = 0; c < stays.size(); ++c)
      for (const StreamTriangle& t : stays[c]) {
        stayIndex_[c].push_back(uint32_t(topInput_.size()));
        topInput_.add(t);
      }
    report_.topTriangles = topInput_.size();
    requireTopFits(topInput_.size(), options_.topTriangles);
  }

  // The top levels sampled and laid out, the buckets spliced in below them, the store written.
  void writeStore(const std::string& out) {
    const Stopwatch clock;
    TopTree top;
    top.oct.origin = frame_.origin;
    top.oct.size = frame_.size;
    addTopNode(*census_, plan_, CellKey{}, buckets_, stayIndex_, top);
    const std::vector<double> topAreas = areasOf(topInput_);
    drawSamples(top.oct, topAreas, params_.c, params_.seed, threads_);
    TreeLayout layout(top.oct, topInput_, topAreas, top.hidden);
    SampleTree head;
    layout.emit(0, head);
    StoreMeta meta{params_,           frame_.origin,     frame_.size,
                   report_.triangles, head.nodes.size(), head.ids.size()};
    for (const auto& [k, u] : layout.splices()) {
      meta.nodes += top.hidden[u].nodes;
      meta.triangles += top.hidden[u].triangles;
    }
    require(meta.triangles == report_.triangles, in().where(),
            "internal: the external build stored " + std::to_string(meta.triangles) + " of " +
                std::to_string(report_.triangles) + " triangles");
    report_.nodes = meta.nodes;
    const std::string outline = outlineText(in().outline());
    meta.outlineBytes = outline.size();
    const StoreAssembly assembly{head, layout.splices(), top, buckets_, *scratch_};
    writeAtomically(out, [&](const std::filesystem::path& tmp) {
      StoreWriter w(tmp, meta);
      assembly.write(w);
      w.append(outline.data(), outline.size());
      w.finish();
    });
    report_.storeBytes = std::filesystem::file_size(out);
    report_.storeSeconds = clock.seconds();
  }

  const TreeParams& params_;
  const ExternalOptions& options_;
  int threads_;
  ExternalReport report_;
  PassInput input_;  // after report_, which its passes count in
  CellOctree frame_;
  std::optional<PartitionSpill> partitions_;
  std::optional<CellCensus> census_;
  Plan plan_;
  std::optional<ScratchArrays> scratch_;
  std::vector<BucketResult> buckets_;
  TriangleInput topInput_;
  std::vector<std::vector<uint32_t>> stayIndex_;  // per top cell: its triangles in topInput_
};

}  // namespace

ExternalOptions optionsForMemory(uint64_t memBytes, const TreeParams& params, int threads) {
  ExternalOptions o;
  o.bucketTriangles = memBytes / 10 * 6 / kBuildBytesPerTriangle / uint64_t(std::max(threads, 1));
  o.bufferTriangles = std::max<uint64_t>(memBytes / 100 * 15 / sizeof(StreamTriangle), 1);
  o.topTriangles = memBytes / 10 / kBuildBytesPerTriangle;
  require(o.bucketTriangles > params.leafTriangles, "--mem-mb",
          "too small: a bucket would hold " + std::to_string(o.bucketTriangles) +
              " triangles, not more than a leaf (" + std::to_string(params.leafTriangles) + ")");
  return o;
}

ExternalReport buildTreeExternal(const TriangleStream& source, const TreeParams& params,
                                 const ExternalOptions& options, int threads,
                                 const std::string& out) {
  validateParams(params);
  require(options.bucketTriangles > params.leafTriangles, "--mem-mb",
          "a bucket must hold more triangles than a leaf");
  return ExternalBuild(source, params, options, threads).run(out);
}

}  // namespace lzb::sampletree
