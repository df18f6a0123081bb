// translation_memo.h — internal to mesh/src: what the fast engine gives element pairs equal up to
// an exact translation, computed once per call (pdd.h, "Translation"): contacts()' records, the
// contact energy's global minimisers.
//
// Inputs:  element pairs (A, B) of one call; `compute`, the call's value of a pair (fast_record in
//          contacts.cpp, fast::global_minimiser in contact_energy.cpp), the same for every pair;
//          `move`, pdd.h's move_positions for that value.
// Outputs: the pair's value, equal bit for bit to compute(A, B).
// Why: a structured mesh against a shifted copy (a grid of cell 2^-k, integer voxels, blocks
// stacked by a whole number of cells) has few element pairs up to translation — 288 among the
// 47,916 box pairs of two 6^3 Kuhn grids half a cell apart — and those are the pairs whose
// parallel faces and edges take the engine's slow ties. The engine computes every pair that
// anchored_pair moves on the moved pair and moves its positions back, so a key of the 21
// moved coordinates (A's first vertex is the origin) names the value exactly: on a hit the
// stored value of the moved pair is moved by the pair's own s0, which is what compute(A, B)
// returns (pdd.h: solve_pair(p) == move_positions(solve_pair(m), s0) whenever the move succeeds,
// global_minimiser likewise; the hot functions return no positions; the rest poses come back
// bit for bit). Where the move fails (a coordinate would leave the double range), compute(A, B)
// runs as given. (The exact
// decision of stage 3 is not memoised: on the grids where pairs repeat its filter and touching
// faces' exact test cost less than a key and a lookup.)
// Cost control: on meshes with no repetition (rotated, unstructured) the moved coordinates are
// all different, so the memo stops itself when, after kProbe lookups, fewer than a quarter hit
// (a key and a hash cost ~50 ns against the pair's ~1-10 us, but the stored records ~1 KB each);
// and it stores at most kMaxEntries records. Neither changes a result, only which pairs are
// computed.
// Threads: tbb::concurrent_unordered_map (insert and find concurrently, no erase). Two threads
// may compute the same key at once; both results are the same bits, the first insert stays.
#pragma once

#include <tbb/concurrent_unordered_map.h>

#include <array>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <string_view>

#include "pdd/pdd.h"

namespace pdd::mesh::detail {

template <class Value>
class TranslationMemo {
 public:
  static constexpr std::size_t kProbe = 4096;
  static constexpr std::size_t kMaxEntries = std::size_t(1) << 16;

  // compute(A, B) -> Value, through the memo. move(Value& v, const fast::AnchoredPair& m, A, B)
  // -> bool turns the value of the moved pair m into the pair's (pdd.h's move_positions), false
  // when it cannot (then compute(A, B) runs as given, as the engine does).
  template <class Compute, class Move>
  Value get(const TetVertices& A, const TetVertices& B, Compute compute, Move move) {
    if (off()) return compute(A, B);
    const std::optional<fast::AnchoredPair> m = fast::anchored_pair(A, B);
    if (!m) return compute(A, B);
    const Key key = key_of(*m);
    Value v;
    const auto found = values_.find(key);
    if (found != values_.end()) {
      v = found->second;
    } else {
      v = compute(m->A, m->B);
      if (values_.size() < kMaxEntries) values_.insert({key, v});
    }
    count(found != values_.end());
    if (!move(v, *m, A, B)) return compute(A, B);
    return v;
  }

 private:
  // A's vertices 1..3 and B's 0..3 of the moved pair (A's first vertex is the origin).
  struct Key {
    std::array<double, 21> x;
    bool operator==(const Key& o) const { return std::memcmp(x.data(), o.x.data(), sizeof x) == 0; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return std::hash<std::string_view>()(std::string_view(reinterpret_cast<const char*>(k.x.data()), sizeof k.x));
    }
  };
  static Key key_of(const fast::AnchoredPair& m) {
    Key k;
    std::memcpy(k.x.data(), &m.A[1], 9 * sizeof(double));
    std::memcpy(k.x.data() + 9, &m.B[0], 12 * sizeof(double));
    return k;
  }
  bool off() const { return off_.load(std::memory_order_relaxed); }
  // After kProbe lookups (and at every doubling), off when fewer than a quarter hit.
  void count(bool hit) {
    const std::size_t n = lookups_.fetch_add(1, std::memory_order_relaxed) + 1;
    const std::size_t h = hit ? hits_.fetch_add(1, std::memory_order_relaxed) + 1 : hits_.load(std::memory_order_relaxed);
    if (n >= kProbe && (n & (n - 1)) == 0 && 4 * h < n) off_.store(true, std::memory_order_relaxed);
  }

  tbb::concurrent_unordered_map<Key, Value, Hash> values_;
  std::atomic<std::size_t> lookups_{0}, hits_{0};
  std::atomic<bool> off_{false};
};

}  // namespace pdd::mesh::detail
