// contacts.cpp — the four stages of pdd::mesh::contacts (pdd/mesh/contacts.h): boxes, CGAL's
// box_intersection_d, the exact decision, the requested variants on all cores.
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "check_indices.h"
#include "translation_memo.h"
#include "pdd/mesh.h"
#include "pdd/rejection.h"

namespace pdd::mesh {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// An element's box for CGAL's box_intersection_d: its bounds, the element index (info()) and a
// unique id (id(): CGAL's tie-break; element index in A, plus the size of A in B). Not CGAL's
// Box_with_info_d<..., ID_EXPLICIT>: that draws its id from a global atomic counter at every
// construction, which the parallel box building contended on.
struct Box : CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_NONE> {
  using Base = CGAL::Box_intersection_d::Box_d<double, 3, CGAL::Box_intersection_d::ID_NONE>;
  using ID = std::size_t;
  std::size_t index = 0, uid = 0;
  Box() = default;
  Box(double lo[3], double hi[3], std::size_t i, std::size_t id) : Base(lo, hi), index(i), uid(id) {}
  std::size_t info() const { return index; }
  ID id() const { return uid; }
};

// Element i's box, grown by `grow` on every side (rounded as written; 0: the element's box).
Box box_of(const Mesh& m, std::size_t i, std::size_t id_offset, double grow = 0) {
  const TetVertices t = element(m, i);
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(std::min(t[0][k], t[1][k]), std::min(t[2][k], t[3][k])) - grow;
    hi[k] = std::max(std::max(t[0][k], t[1][k]), std::max(t[2][k], t[3][k])) + grow;
  }
  return Box(lo, hi, i, id_offset + i);
}

bool share_vertex(const Mesh& m, std::size_t a, std::size_t b) {
  for (std::size_t u : m.tets[a])
    for (std::size_t v : m.tets[b])
      if (u == v) return true;
  return false;
}

// Stage 1: the box of every valid element, in element order (the others are listed in
// `skipped`, with the reason; built only for them).
std::vector<Box> valid_boxes(const Mesh& m, char which, std::size_t id_offset,
                             std::vector<SkippedElement>& skipped) {
  const std::size_t n = m.tets.size();
  std::vector<Box> boxes(n);
  std::vector<char> ok(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      ok[i] = !element_problem(m, i, which);
      if (ok[i]) boxes[i] = box_of(m, i, id_offset);
    }
  });
  if (std::find(ok.begin(), ok.end(), 0) == ok.end()) return boxes;
  std::vector<Box> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (ok[i])
      out.push_back(boxes[i]);
    else
      skipped.push_back({which, i, *element_problem(m, i, which)});
  return out;
}

// Positions of a rest pose in the record's number type.
template <class R>
Positions<R> rest(const TetVertices& T) {
  Positions<R> p;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) p[i][k] = R(T[i][k]);
  return p;
}

// definitions §9's fields as when kGlobal is not requested (pdd/mesh/contacts.h): 0, no normal, the rest pose,
// no lower bound.
template <class R>
void clear_global(PairResult<R>& r, const TetVertices& A, const TetVertices& B) {
  r.pdd2_global = R(0);
  r.pdd2_global_normal.reset();
  r.q1_A_global = rest<R>(A);
  r.q1_B_global = rest<R>(B);
  r.pdd2_global_lower.reset();
}

// The record of one intersecting pair with only the requested variants (fast engine).
PairResult<double> fast_record(const TetVertices& A, const TetVertices& B, unsigned variants) {
  PairResult<double> r;
  // One solve_pair: for pdd2 and global (their positions come only from it; global's hot path
  // is also slower than solve_pair on mesh pairs, pdd/mesh/contacts.h), eq11 (no separate call),
  // pdd2_relaxed and pdd2_accel6 (solve_pair keeps them against pdd2: value_relations.h), and two
  // or more variants besides rigid; it computes the asked values and those they are kept
  // against, no others (SolveOptions::values).
  const bool needs_record = (variants & (kPdd2 | kEq11 | kGlobal | kRelaxed | kAccel6)) ||
                            __builtin_popcount(variants & ~unsigned(kRigid)) >= 2;
  if (needs_record) {
    // definitions §9's search only when asked: it is most of solve_pair's time; the other
    // values only as asked too (solve_options.h: not asked, 0 and no label)
    fast::SolveOptions options;
    options.with_global = (variants & kGlobal) != 0;
    options.values = variants & ~unsigned(kGlobal);
    r = fast::solve_pair(TetPair{"", {}, A, B}, options);
    if (r.error) return r;
    if (!(variants & kGlobal)) clear_global(r, A, B);
    return r;
  }
  r.intersecting = true;
  r.q1_A = A;
  r.q1_B = B;
  clear_global(r, A, B);
  auto put = [&](const fast::Depth& d, double& v, std::optional<DirectionLabel>* label) {
    if (d.status != fast::DepthStatus::Ok) r.error = kNotRepresentable;
    v = d.pd2;
    if (label) *label = d.dir;
  };
  if ((variants & kRigid) && (variants & kAccel1)) {
    const fast::RigidAndAccel1 d = fast::rigid_pd2_and_accel1(A, B);
    put(d.rigid, r.rigid_pd2, &r.rigid_dir);
    put(d.accel1, r.pdd2_accel1, nullptr);
  } else {
    if (variants & kRigid) put(fast::rigid_pd2(A, B), r.rigid_pd2, &r.rigid_dir);
    if (variants & kAccel1) put(fast::pdd2_accel(A, B, 1), r.pdd2_accel1, nullptr);
  }
  // solve_pair keeps pdd2_static <= rigid_pd2 (definitions §5, value_relations.h): the same
  // here, against the same bound, for the same doubles.
  if (variants & kStatic) {
    put(fast::pdd2_static(A, B), r.pdd2_static, &r.pdd2_static_dir);
    const double bound = (variants & kRigid) ? r.rigid_pd2 : fast::rigid_pd2(A, B).pd2;
    if (r.pdd2_static > bound) r.pdd2_static = bound;
  }
  return r;
}

std::vector<std::array<std::size_t, 2>> pairs_of_boxes(const Mesh& A, std::vector<Box>& ba,
                                                       std::vector<Box>* bbp,
                                                       const BroadphaseOptions& options);

// The records' storage (~0.9 KB a record: PairResult's values, positions and strings) asked
// for in transparent huge pages where the kernel gives them on request (Linux, THP "madvise";
// under "always" it does anyway, under "never" this changes nothing). glibc maps a block above
// its largest mmap threshold (32 MiB: ~36,000 records) afresh on every call, and the first
// touch of each of its 4 KB pages (the records' construction) is a page fault: on a 2-CPU VM
// ~10 us a page, ~2 us a record, near the engine's own work on a pair for the default variants
// and several times it for rigid and accel1 (docs/performance.md, "Direction tests over
// integers"). One 2 MB page takes the faults of 512. A smaller block comes back from the heap,
// without faults, only where an earlier call left it there: the first call of a process (every
// `pdd mesh` run) touches fresh heap pages too, and so does a call after the heap's top was
// given back. So every 2 MB-aligned part of the buffer is advised: on two 8^3 Kuhn grids of cell
// 1/8 half a cell apart along (1, 1, 1) (10,170 records, 10 MB), `pdd mesh --variants
// rigid,accel1 --threads 1` took 0.037 s in the depth stage with only buffers of 32 MiB or more
// advised, 0.021 s with these. The advice is a hint: its failure changes nothing.
void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data, (void)bytes;
#endif
}

template <class R>
Contacts<R> run(const Mesh& A, const Mesh* B, const ContactOptions& options) {
  detail::check_indices(A, 'A');
  if (B) detail::check_indices(*B, 'B');
  const Mesh& BB = B ? *B : A;
  const auto cancelled = [&] { return options.cancel && options.cancel->load(std::memory_order_relaxed); };
  const auto stop_if_cancelled = [&] {
    if (cancelled()) throw Cancelled();
  };
  Contacts<R> out;
  out.elements_a = A.tets.size();
  out.elements_b = B ? B->tets.size() : 0;

  auto t = Clock::now();
  std::vector<Box> ba = valid_boxes(A, 'A', 0, out.skipped);
  std::vector<Box> bb = B ? valid_boxes(*B, 'B', A.tets.size(), out.skipped) : std::vector<Box>{};
  out.seconds_boxes = since(t);
  stop_if_cancelled();

  t = Clock::now();
  BroadphaseOptions bo;
  bo.drop_shared_vertex = !B;  // self-contact: pairs sharing a vertex are not candidates
  // CGAL's parallel self-intersection (16 subproblems on 4 copies of the boxes) took twice the
  // time of the sequential one on a ball of 98120 elements (1.39 s against 0.67 s, 2 cores).
  bo.parallel = B != nullptr;
  std::vector<std::array<std::size_t, 2>> cand = pairs_of_boxes(A, ba, B ? &bb : nullptr, bo);
  out.box_pairs = cand.size();
  out.seconds_broadphase = since(t);
  stop_if_cancelled();

  // Stage 3: the exact decision (definitions §4): fast::interiors_intersect, a certified
  // separating-axis filter in doubles that decides almost every box pair in about 100 ns, and
  // rigid_pd2's exact decision for the rest (touching or nearly touching pairs, parallel edges).
  t = Clock::now();
  std::vector<char> hit(cand.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      if (cancelled()) return;
                      for (std::size_t k = r.begin(); k != r.end(); ++k)
                        hit[k] = fast::interiors_intersect(element(A, cand[k][0]),
                                                           element(BB, cand[k][1]));
                    });
  std::vector<std::size_t> hits;
  for (std::size_t k = 0; k < cand.size(); ++k)
    if (hit[k]) hits.push_back(k);
  out.seconds_decision = since(t);
  stop_if_cancelled();

  // Stage 4: the variants, through the translation memo (translation_memo.h: the same bits).
  t = Clock::now();
  detail::TranslationMemo<PairResult<double>> records;
  // The records (~1 KB each) constructed a chunk at a time, the cancel flag checked between
  // chunks: 542,400 of them (a torus against 200 copies of a box, ~0.5 GB) took ~1.4 s of first
  // touches in one resize, during which Ctrl-C waited. Within the reserved capacity: no move.
  constexpr std::size_t kChunk = std::size_t(1) << 14;
  out.pairs.reserve(hits.size());
  advise_huge_pages(out.pairs.data(), out.pairs.capacity() * sizeof(Contact<R>));
  for (std::size_t k = 0; k < hits.size(); k += kChunk) {
    stop_if_cancelled();
    out.pairs.resize(std::min(hits.size(), k + kChunk));
  }
  if (options.progress) options.progress(0, hits.size());
  tbb::parallel_for(std::size_t{0}, hits.size(), [&](std::size_t h) {
    if (cancelled()) return;
    const std::size_t k = hits[h];
    Contact<R>& c = out.pairs[h];
    c.a = cand[k][0];
    c.b = cand[k][1];
    const TetVertices Ta = element(A, c.a), Tb = element(BB, c.b);
    if constexpr (std::is_same_v<R, double>) {
      c.result = records.get(
          Ta, Tb, [&](const TetVertices& a, const TetVertices& b) { return fast_record(a, b, options.variants); },
          [](PairResult<double>& r, const fast::AnchoredPair& m, const TetVertices& a, const TetVertices& b) {
            return fast::move_positions(r, m, a, b);
          });
    } else {
      reference::SolveOptions solve;
      solve.with_global = options.variants & kGlobal;
      c.result = reference::solve_pair(TetPair{"", {}, Ta, Tb}, solve);
      if (!solve.with_global && !c.result.error) clear_global(c.result, Ta, Tb);
    }
    if constexpr (std::is_same_v<R, double>) {
      if (options.fast_pair) options.fast_pair(h, c);
    } else {
      if (options.exact_pair) options.exact_pair(h, c);
    }
    if (options.progress) options.progress(1, hits.size());
  });
  stop_if_cancelled();
  out.seconds_depth = since(t);
  return out;
}

}  // namespace

TetVertices element(const Mesh& m, std::size_t i) {
  TetVertices t;
  for (int k = 0; k < 4; ++k) t[k] = m.vertices[m.tets[i][k]];
  return t;
}

std::optional<std::string> element_problem(const Mesh& m, std::size_t i, char which) {
  const TetVertices t = element(m, i);
  for (int v = 0; v < 4; ++v)
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(t[v][k])) {
        std::ostringstream o;
        const auto source = m.vertex_sources.find(m.tets[i][v]);
        o << "element " << i << " of mesh " << which << ": vertex " << v << " (mesh vertex "
          << m.tets[i][v] << (source == m.vertex_sources.end() ? "" : ": " + source->second)
          << ") coordinate " << "xyz"[k] << " is not finite (" << t[v][k] << ")";
        return o.str();
      }
  using P = CGAL::Epick::Point_3;
  auto p = [&](int v) { return P(t[v][0], t[v][1], t[v][2]); };
  if (CGAL::orientation(p(0), p(1), p(2), p(3)) == CGAL::COPLANAR)  // exact predicate
    return "element " + std::to_string(i) + " of mesh " + which +
           " is flat: its four vertices are coplanar (volume 0)";
  return std::nullopt;
}

namespace {

// Stage 2 on boxes (box_pairs, pdd/mesh/broadphase.h); ba, bb are reordered (and pruned). bb null: self.
std::vector<std::array<std::size_t, 2>> pairs_of_boxes(const Mesh& A, std::vector<Box>& ba,
                                                       std::vector<Box>* bbp,
                                                       const BroadphaseOptions& options) {
  using Pairs = std::vector<std::array<std::size_t, 2>>;
  tbb::enumerable_thread_specific<Pairs> found;  // the callback runs on several threads
  Pairs direct;  // sequential runs: no thread-local lookup per pair
  auto sink = [&]() -> Pairs& { return options.parallel ? found.local() : direct; };
  using CGAL::Box_intersection_d::HALF_OPEN;
  // Below `cutoff` boxes CGAL scans instead of recursing. Element boxes of a mesh share many
  // coordinates exactly (neighbours share vertices), and the segment tree's splits degrade on
  // them: on two 72682-element balls (make-meshes.sh --large) the default cutoff 10 took 3.2 s,
  // 1000 took 0.54 s, 10000 0.18 s, 30000 0.16 s; on the small fixtures all take about 1 ms.
  // On the boxes left after pruning (about 1500 + 1500 of two 10^5-element balls) 100-300 is
  // best (1.8 ms) and 10000 takes 4.7 ms: the cutoff grows with the number of boxes, n / 20.
  const auto cutoff_for = [](std::size_t n) { return std::ptrdiff_t(std::max<std::size_t>(100, n / 20)); };
  auto run = [&](auto tag, auto&&... args) {
    using Tag = decltype(tag);
    std::size_t n = ba.size();
    if constexpr (sizeof...(args) == 2) n += std::size_t(std::distance(args...));
    const std::ptrdiff_t cutoff = cutoff_for(n);
    if constexpr (sizeof...(args) == 2)
      CGAL::box_intersection_d<Tag>(ba.begin(), ba.end(), args...,
                                    [&](const Box& x, const Box& y) {
                                      sink().push_back({x.info(), y.info()});
                                    },
                                    cutoff, HALF_OPEN, CGAL::Box_intersection_d::BIPARTITE);
    else
      CGAL::box_self_intersection_d<Tag>(
          ba.begin(), ba.end(),
          [&](const Box& x, const Box& y) {
            if (options.drop_shared_vertex && share_vertex(A, x.info(), y.info())) return;
            sink().push_back({std::min(x.info(), y.info()), std::max(x.info(), y.info())});
          },
          cutoff, HALF_OPEN);
  };
  if (bbp) {
    std::vector<Box>& bb = *bbp;
    if (options.prune) {
      // Only a box that overlaps the other mesh's bounding box (the union of its boxes) can
      // overlap one of its boxes: with half-open boxes, x and y overlap iff x.lo < y.hi and
      // y.lo < x.hi on every axis, and y.hi <= U.hi, U.lo <= y.lo for y in U. The same strict
      // test against U keeps every overlapping pair and drops no box that has one.
      auto bounds = [](const std::vector<Box>& v) {
        std::array<double, 6> u = {HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        for (const Box& x : v)
          for (int k = 0; k < 3; ++k) {
            u[k] = std::min(u[k], x.min_coord(k));
            u[3 + k] = std::max(u[3 + k], x.max_coord(k));
          }
        return u;
      };
      auto keep = [](std::vector<Box>& v, const std::array<double, 6>& u) {
        v.erase(std::remove_if(v.begin(), v.end(),
                               [&](const Box& x) {
                                 for (int k = 0; k < 3; ++k)
                                   if (!(x.min_coord(k) < u[3 + k] && u[k] < x.max_coord(k)))
                                     return true;
                                 return false;
                               }),
                v.end());
      };
      // Repeated while it removes boxes (at most 4 rounds): each round shrinks both bounding
      // boxes (two overlapping balls: the first round leaves two slabs, the second the lens).
      for (int round = 0; round < 4; ++round) {
        const std::size_t before = ba.size() + bb.size();
        const std::array<double, 6> ua = bounds(ba), ub = bounds(bb);
        keep(ba, ub);
        keep(bb, ua);
        if (ba.size() + bb.size() == before) break;
      }
    }
    if (options.parallel)
      run(CGAL::Parallel_tag{}, bb.begin(), bb.end());
    else
      run(CGAL::Sequential_tag{}, bb.begin(), bb.end());
  } else {
    if (options.parallel)
      run(CGAL::Parallel_tag{});
    else
      run(CGAL::Sequential_tag{});
  }
  Pairs out = std::move(direct);
  std::size_t n = out.size();
  for (const Pairs& p : found) n += p.size();
  out.reserve(n);
  for (const Pairs& p : found) out.insert(out.end(), p.begin(), p.end());
  tbb::parallel_sort(out.begin(), out.end());
  return out;
}

}  // namespace

namespace {
// The boxes of elements e, each grown by `grow` on every side (0: the elements' own boxes).
std::vector<Box> boxes_of(const Mesh& m, const std::vector<std::size_t>& e, std::size_t id_offset, double grow = 0) {
  std::vector<Box> v(e.size());
  tbb::parallel_for(std::size_t{0}, e.size(), [&](std::size_t k) {
    v[k] = box_of(m, e[k], id_offset, grow);
  });
  return v;
}
}  // namespace

namespace detail {
std::vector<std::array<std::size_t, 2>> grown_box_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                        const Mesh* B, const std::vector<std::size_t>& eb,
                                                        double grow, const BroadphaseOptions& options) {
  std::vector<Box> ba = boxes_of(A, ea, 0, grow);
  if (!B) return pairs_of_boxes(A, ba, nullptr, options);
  std::vector<Box> bb = boxes_of(*B, eb, A.tets.size(), grow);
  return pairs_of_boxes(A, ba, &bb, options);
}
}  // namespace detail

std::vector<std::array<std::size_t, 2>> box_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                  const Mesh& B, const std::vector<std::size_t>& eb,
                                                  const BroadphaseOptions& options) {
  std::vector<Box> ba = boxes_of(A, ea, 0);
  std::vector<Box> bb = boxes_of(B, eb, A.tets.size());
  return pairs_of_boxes(A, ba, &bb, options);
}

std::vector<std::array<std::size_t, 2>> box_pairs_self(const Mesh& A, const std::vector<std::size_t>& ea,
                                                       const BroadphaseOptions& options) {
  std::vector<Box> ba = boxes_of(A, ea, 0);
  return pairs_of_boxes(A, ba, nullptr, options);
}

unsigned parse_variants(const std::string& list) {
  unsigned v = 0;
  std::stringstream in(list);
  std::string w;
  while (std::getline(in, w, ',')) {
    if (w == "all") {
      v |= kAllVariants;
      continue;
    }
    std::size_t k = 0;
    while (k < kVariantCount && w != kVariantNames[k]) ++k;
    if (k == kVariantCount) {
      std::string known;
      for (const char* name : kVariantNames) known += std::string(name) + ", ";
      throw std::invalid_argument("unknown variant '" + w + "' (" + known + "all)");
    }
    v |= 1u << k;
  }
  if (!v) throw std::invalid_argument("no variant named");
  return v;
}

std::string variant_names(unsigned variants) {
  std::string s;
  for (std::size_t k = 0; k < kVariantCount; ++k)
    if (variants & (1u << k)) s += (s.empty() ? "" : ",") + std::string(kVariantNames[k]);
  return s;
}

Contacts<double> contacts(const Mesh& A, const Mesh& B, const ContactOptions& o) { return run<double>(A, &B, o); }
Contacts<double> contacts_self(const Mesh& A, const ContactOptions& o) { return run<double>(A, nullptr, o); }
Contacts<Rational> contacts_exact(const Mesh& A, const Mesh& B, const ContactOptions& o) {
  return run<Rational>(A, &B, o);
}
Contacts<Rational> contacts_exact_self(const Mesh& A, const ContactOptions& o) {
  return run<Rational>(A, nullptr, o);
}

namespace detail {

void check_indices(const Mesh& m, char which) {
  for (std::size_t i = 0; i < m.tets.size(); ++i)
    for (std::size_t v : m.tets[i])
      if (v >= m.vertices.size()) {
        std::ostringstream o;
        o << "element " << i << " of mesh " << which << " refers to vertex " << v << ", but the mesh has "
          << m.vertices.size() << " vertices";
        throw std::invalid_argument(o.str());
      }
}

}  // namespace detail
}  // namespace pdd::mesh
