// contact_list.cpp — the contact stage's candidate list (contact_list.h).
#include "contact_list.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "../resolve.h"
#include "geometry.h"

namespace pdd::mesh::detail {
namespace {

// The growth g of the boxes: kGrowShare of the mean edge length of the elements (RMS over each
// element's six edges), at least kGrowUlp of the largest |coordinate|.
// Why the list holds every overlapping pair of elements that have not escaped: a vertex whose
// computed |x - x_build| per coordinate is at most g/2 is truly at most g/2 (1 + 2^-52) away;
// an element's box then has lo >= lo_build - g/2 (1 + 2^-52), and its grown
// lo' = fl(lo_build - g) is at most lo_build - g + 2^-53 (|lo_build| + g). The second is below
// the first when g (1/2 - 2^-52) >= 2^-53 |lo_build|, which g >= kGrowUlp |x|max = 2^-40 |x|max
// ensures with a wide margin; the same for hi. Half-open boxes inside the grown boxes overlap
// only where their grown boxes do, and the exact decision decides the candidates.
// The share: a quarter of an edge holds the list over many rounds for most elements while the
// grown boxes meet only about one ring of elements more than the boxes do.
constexpr double kGrowShare = 0.25;
constexpr double kGrowUlp = 0x1p-40;
// Escaped elements (a vertex further than g/2 from its build position) are paired afresh each
// round by box intersection against all elements; beyond kRebuildShare of the elements escaped,
// the list is rebuilt (one broadphase over all grown boxes costs about that much).
constexpr double kRebuildShare = 0.25;

double rms_edge(const TetVertices& t) {
  double s = 0;
  for (const auto& e : kEdges) {
    const Vec3d d = sub(t[e[1]], t[e[0]]);
    s += dot(d, d);
  }
  return std::sqrt(s / 6);
}

// Adds the RMS edges of elements e of m to `sum`, grows `coord` to the largest |x| of m.
void measure(const Mesh& m, const std::vector<std::size_t>& e, double& sum, double& coord) {
  for (std::size_t i : e) sum += rms_edge(element(m, i));
  for (const Vec3d& v : m.vertices)
    for (double x : v) coord = std::max(coord, std::abs(x));
}

// Per element of m: changed (a vertex differs from `last`, bit for bit) and escaped (a vertex
// further than `limit` from `built` in a coordinate, or not finite).
void mark(const Mesh& m, const std::vector<Vec3d>& built, const std::vector<Vec3d>& last, double limit,
          std::vector<char>& changed, std::vector<char>& escaped) {
  const std::size_t nv = m.vertices.size();
  std::vector<char> moved(nv), away(nv);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nv, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      moved[v] = m.vertices[v] != last[v];
      bool far = false;
      for (int k = 0; k < 3; ++k) far |= !(std::abs(m.vertices[v][k] - built[v][k]) <= limit);
      away[v] = far;
    }
  });
  changed.assign(m.tets.size(), 0);
  escaped.assign(m.tets.size(), 0);
  for (std::size_t e = 0; e < m.tets.size(); ++e)
    for (std::size_t v : m.tets[e]) changed[e] |= moved[v], escaped[e] |= away[v];
}

// The box (lo, hi) of every element of m.
using Bounds = std::array<double, 6>;
void boxes_of(const Mesh& m, std::vector<Bounds>& box) {
  box.resize(m.tets.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.tets.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t e = r.begin(); e != r.end(); ++e) {
      const TetVertices t = element(m, e);
      for (int k = 0; k < 3; ++k) {
        box[e][k] = std::min(std::min(t[0][k], t[1][k]), std::min(t[2][k], t[3][k]));
        box[e][3 + k] = std::max(std::max(t[0][k], t[1][k]), std::max(t[2][k], t[3][k]));
      }
    }
  });
}

// Whether the open boxes overlap: a pair whose interiors intersect has a point strictly inside
// both boxes, so a pair failing this test does not intersect (the comparisons are exact).
bool open_boxes_overlap(const Bounds& x, const Bounds& y) {
  for (int k = 0; k < 3; ++k)
    if (!(x[k] < y[3 + k] && y[k] < x[3 + k])) return false;
  return true;
}

std::vector<std::size_t> marked(const std::vector<std::size_t>& elems, const std::vector<char>& flag) {
  std::vector<std::size_t> out;
  for (std::size_t e : elems)
    if (flag[e]) out.push_back(e);
  return out;
}

bool share_vertex(const Mesh& m, std::size_t a, std::size_t b) {
  for (std::size_t u : m.tets[a])
    for (std::size_t v : m.tets[b])
      if (u == v) return true;
  return false;
}

}  // namespace

bool ContactList::same_input(const Mesh& a, const std::vector<std::size_t>& ea, const Mesh* b,
                             const std::vector<std::size_t>& eb) const {
  if (!valid_ || self_ != (b == nullptr) || sa_.mesh != &a || sa_.elems != ea ||
      sa_.built.size() != a.vertices.size())
    return false;
  return !b || (sb_.mesh == b && sb_.elems == eb && sb_.built.size() == b->vertices.size());
}

void ContactList::build(const Mesh& a, const std::vector<std::size_t>& ea, const Mesh* b,
                        const std::vector<std::size_t>& eb) {
  valid_ = false;
  self_ = b == nullptr;
  double sum = 0, coord = 0;
  measure(a, ea, sum, coord);
  if (b) measure(*b, eb, sum, coord);
  const std::size_t n = ea.size() + (b ? eb.size() : 0);
  grow_ = std::max(n ? kGrowShare * sum / double(n) : 0.0, kGrowUlp * coord);
  if (!std::isfinite(grow_) || !(grow_ > 0)) return;
  BroadphaseOptions bo;
  bo.drop_shared_vertex = !b;
  bo.parallel = b != nullptr;  // as intersecting_pairs: the sequential self-intersection is faster
  candidates_ = grown_box_pairs(a, ea, b, eb, grow_, bo);
  hit_.assign(candidates_.size(), 0);
  const auto seen = [](const Mesh& m, const std::vector<std::size_t>& e) {
    return Seen{&m, e, m.vertices, m.vertices, std::vector<char>(m.tets.size(), 1), std::vector<char>(m.tets.size(), 0)};
  };
  sa_ = seen(a, ea);
  if (b) sb_ = seen(*b, eb);
  valid_ = true;
  ++builds_;
}

// The pairs with an escaped element, by box intersection of the escaped elements' boxes with
// all elements' boxes at the current positions, decided exactly; sorted.
std::vector<ContactList::Pair> ContactList::escaped_pairs(const Mesh& a, const Mesh* b) const {
  BroadphaseOptions bo;  // bipartite: prune to the other side's bounds, on all cores
  std::vector<Pair> cand;
  const std::vector<std::size_t> xa = marked(sa_.elems, sa_.escaped);
  if (!b) {
    if (!xa.empty())
      for (const Pair& p : box_pairs(a, xa, a, sa_.elems, bo))
        if (p[0] != p[1] && !share_vertex(a, p[0], p[1])) cand.push_back({std::min(p[0], p[1]), std::max(p[0], p[1])});
  } else {
    const std::vector<std::size_t> xb = marked(sb_.elems, sb_.escaped);
    if (!xa.empty()) cand = box_pairs(a, xa, *b, sb_.elems, bo);
    if (!xb.empty())
      for (const Pair& p : box_pairs(a, sa_.elems, *b, xb, bo)) cand.push_back(p);
  }
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  const Mesh& bb = b ? *b : a;
  std::vector<char> hit(cand.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k)
      hit[k] = fast::interiors_intersect(element(a, cand[k][0]), element(bb, cand[k][1]));
  });
  std::vector<Pair> out;
  for (std::size_t k = 0; k < cand.size(); ++k)
    if (hit[k]) out.push_back(cand[k]);
  return out;
}

std::vector<ContactList::Pair> ContactList::pairs(const Mesh& a, const std::vector<std::size_t>& ea,
                                                  const Mesh* b, const std::vector<std::size_t>& eb) {
  std::size_t escaped = 0;
  if (same_input(a, ea, b, eb)) {
    mark(a, sa_.built, sa_.last, grow_ / 2, sa_.changed, sa_.escaped);
    escaped = std::size_t(std::count(sa_.escaped.begin(), sa_.escaped.end(), 1));
    if (b) {
      mark(*b, sb_.built, sb_.last, grow_ / 2, sb_.changed, sb_.escaped);
      escaped += std::size_t(std::count(sb_.escaped.begin(), sb_.escaped.end(), 1));
    }
  }
  const std::size_t n = ea.size() + (b ? eb.size() : 0);
  if (!same_input(a, ea, b, eb) || double(escaped) > kRebuildShare * double(n)) {
    build(a, ea, b, eb);
    if (!valid_) return intersecting_pairs(a, ea, b, eb);  // no finite growth: a fresh broadphase
    escaped = 0;
  }
  sa_.last = a.vertices;
  if (b) sb_.last = b->vertices;
  const Mesh& bb = b ? *b : a;
  const Seen& sB = b ? sb_ : sa_;
  // The current boxes, a test far cheaper than the exact decision that most candidates fail.
  boxes_of(a, box_a_);
  if (b) boxes_of(*b, box_b_);
  const std::vector<Bounds>& box_B = b ? box_b_ : box_a_;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates_.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k) {
                        const Pair& p = candidates_[k];
                        if (sa_.escaped[p[0]] || sB.escaped[p[1]])
                          hit_[k] = 0;  // decided with the escaped pairs below
                        else if (sa_.changed[p[0]] || sB.changed[p[1]])
                          hit_[k] = open_boxes_overlap(box_a_[p[0]], box_B[p[1]]) &&
                                    fast::interiors_intersect(element(a, p[0]), element(bb, p[1]));
                      }
                    });
  std::vector<Pair> out;
  for (std::size_t k = 0; k < candidates_.size(); ++k)
    if (hit_[k]) out.push_back(candidates_[k]);
  if (escaped == 0) return out;  // grown_box_pairs is sorted by (a, b)
  const std::vector<Pair> more = escaped_pairs(a, b);
  std::vector<Pair> all(out.size() + more.size());
  std::merge(out.begin(), out.end(), more.begin(), more.end(), all.begin());
  return all;
}

}  // namespace pdd::mesh::detail
