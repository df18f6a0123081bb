// pair_memo.h — internal to fast/src: per-thread memos of one pair's per-label results.
//
// The values of one solve_pair (rigid_pd2, pdd2_static, pdd2, pdd2_accel, their refinements and
// tie orders) ask the same exact and compensated quantities of the same candidates: on aligned
// contacts about half of them are asked again by another value. A PairMemo keeps the answers
// for the last pair seen on this thread, keyed by the pair's coordinates (bit for bit) and a
// small key (a label and whatever else the answer depends on); every memoised function is pure
// in those, so a hit returns exactly what the computation would. Another pair clears it.
//
// Input:  the pair (A, B), a key, and the computation `f(Value&)` (returning its own verdict).
// Output: the memoised verdict and value, or f's (kept while there is room: kEntries).
// Written by hand: a few compares of 24 doubles and a short linear scan, where a general cache
// (hashing 192 bytes a call, allocation) would cost what it saves.
#pragma once

#include <cstring>

#include "pdd/direction_label.h"
#include "pdd/tet_pair.h"

namespace pdd::fast::detail {

// A label in 10 bits (kind 2, a 3, b 3, orientation 2): the keys' common part.
inline unsigned label_key(const DirectionLabel& l) {
  return unsigned(l.kind) | unsigned(l.a) << 2 | unsigned(l.b) << 5 | unsigned(l.orientation) << 8;
}

template <class Value, int kEntries>
class PairMemo {
 public:
  template <class F>
  bool get(const TetVertices& A, const TetVertices& B, unsigned key, Value& out, F&& f) {
    bool ok = false;
    if (find(A, B, key, out, ok)) return ok;
    const unsigned pair = pair_;
    ok = f(out);
    // (kept only for the pair it was asked for: f may have asked this memo of another pair)
    if (pair == pair_ && n_ < kEntries) key_[n_] = key, value_[n_] = out, ok_[n_] = ok, ++n_;
    return ok;
  }

  // Whether the pair's key is kept (then its value and verdict in out and ok); nothing computed.
  bool find(const TetVertices& A, const TetVertices& B, unsigned key, Value& out, bool& ok) {
    if (!(valid_ && same(A_, A) && same(B_, B))) A_ = A, B_ = B, valid_ = true, n_ = 0, ++pair_;
    for (int i = 0; i < n_; ++i)
      if (key_[i] == key) {
        out = value_[i];
        ok = ok_[i];
        return true;
      }
    return false;
  }

 private:
  static bool same(const TetVertices& X, const TetVertices& Y) { return std::memcmp(&X, &Y, sizeof X) == 0; }
  TetVertices A_{}, B_{};
  bool valid_ = false;
  unsigned pair_ = 0;  // counts the pairs seen
  int n_ = 0;
  unsigned key_[kEntries];
  Value value_[kEntries];
  bool ok_[kEntries];
};

}  // namespace pdd::fast::detail
