// contacts.cpp — the four stages of pdd::mesh::contacts (mesh.h): boxes, CGAL's
// box_intersection_d, the exact decision, the requested variants on all cores.
#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "pdd/mesh.h"
#include "pdd/rejection.h"

namespace pdd::mesh {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t,
                                                      CGAL::Box_intersection_d::ID_EXPLICIT>;

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

Box box_of(const Mesh& m, std::size_t i) {
  const TetVertices t = element(m, i);
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(std::min(t[0][k], t[1][k]), std::min(t[2][k], t[3][k]));
    hi[k] = std::max(std::max(t[0][k], t[1][k]), std::max(t[2][k], t[3][k]));
  }
  return Box(lo, hi, i);
}

bool share_vertex(const Mesh& m, std::size_t a, std::size_t b) {
  for (std::size_t u : m.tets[a])
    for (std::size_t v : m.tets[b])
      if (u == v) return true;
  return false;
}

// Stage 1: the valid elements (others listed in `skipped`).
std::vector<std::size_t> valid_elements(const Mesh& m, char which, std::vector<SkippedElement>& skipped) {
  std::vector<char> ok(m.tets.size());
  std::vector<std::optional<std::string>> why(m.tets.size());
  tbb::parallel_for(std::size_t{0}, m.tets.size(), [&](std::size_t i) {
    why[i] = element_problem(m, i, which);
    ok[i] = !why[i];
  });
  std::vector<std::size_t> out;
  out.reserve(m.tets.size());
  for (std::size_t i = 0; i < m.tets.size(); ++i)
    if (ok[i])
      out.push_back(i);
    else
      skipped.push_back({which, i, *why[i]});
  return out;
}

// The record of one intersecting pair with only the requested variants (fast engine).
PairResult<double> fast_record(const TetVertices& A, const TetVertices& B, unsigned variants,
                               const fast::Depth* rigid) {
  PairResult<double> r;
  const bool needs_record = (variants & (kPdd2 | kEq11)) ||
                            __builtin_popcount(variants & ~unsigned(kRigid)) >= 2;
  if (needs_record) {  // one solve_pair is cheaper than two separate variants
    r = fast::solve_pair(TetPair{"", {}, A, B});
    if (r.error) return r;
    for (std::size_t k = 0; k < kValueCount; ++k)
      if (!(variants & (1u << k))) {
        record_value(r, k) = 0;
        if (kLabelOfValue[k] >= 0) record_label(r, kLabelOfValue[k]).reset();
      }
    if (!(variants & kPdd2)) r.q1_A = A, r.q1_B = B;
    return r;
  }
  r.intersecting = true;
  r.q1_A = A;
  r.q1_B = B;
  auto put = [&](const fast::Depth& d, double& v, std::optional<DirectionLabel>* label) {
    if (d.status != fast::DepthStatus::Ok) r.error = kNotRepresentable;
    v = d.pd2;
    if (label) *label = d.dir;
  };
  if (variants & kRigid) put(rigid ? *rigid : fast::rigid_pd2(A, B), r.rigid_pd2, &r.rigid_dir);
  if (variants & kStatic) put(fast::pdd2_static(A, B), r.pdd2_static, &r.pdd2_static_dir);
  if (variants & kRelaxed) put(fast::pdd2_relaxed(A, B), r.pdd2_relaxed, &r.pdd2_relaxed_dir);
  if (variants & kAccel1) put(fast::pdd2_accel(A, B, 1), r.pdd2_accel1, nullptr);
  if (variants & kAccel6) put(fast::pdd2_accel(A, B, 6), r.pdd2_accel6, nullptr);
  return r;
}

template <class R>
Contacts<R> run(const Mesh& A, const Mesh* B, const ContactOptions& options) {
  check_indices(A, 'A');
  if (B) check_indices(*B, 'B');
  const Mesh& BB = B ? *B : A;
  Contacts<R> out;
  out.elements_a = A.tets.size();
  out.elements_b = B ? B->tets.size() : 0;

  auto t = Clock::now();
  const std::vector<std::size_t> ea = valid_elements(A, 'A', out.skipped);
  const std::vector<std::size_t> eb = B ? valid_elements(*B, 'B', out.skipped) : std::vector<std::size_t>{};
  out.seconds_boxes = since(t);

  t = Clock::now();
  std::vector<std::array<std::size_t, 2>> cand = box_pairs(A, ea, B, eb);
  if (!B)
    cand.erase(std::remove_if(cand.begin(), cand.end(),
                              [&](const auto& p) { return share_vertex(A, p[0], p[1]); }),
               cand.end());
  out.box_pairs = cand.size();
  out.seconds_broadphase = since(t);

  // Stage 3: the exact decision (rigid PD² > 0; SPEC §8 makes 0 exact).
  t = Clock::now();
  std::vector<fast::Depth> rigid(cand.size());
  tbb::parallel_for(std::size_t{0}, cand.size(), [&](std::size_t k) {
    rigid[k] = fast::rigid_pd2(element(A, cand[k][0]), element(BB, cand[k][1]));
  });
  std::vector<std::size_t> hits;
  for (std::size_t k = 0; k < cand.size(); ++k)
    if (rigid[k].status != fast::DepthStatus::Ok || rigid[k].pd2 > 0) hits.push_back(k);
  out.seconds_decision = since(t);

  // Stage 4: the variants.
  t = Clock::now();
  out.pairs.resize(hits.size());
  tbb::parallel_for(std::size_t{0}, hits.size(), [&](std::size_t h) {
    const std::size_t k = hits[h];
    Contact<R>& c = out.pairs[h];
    c.a = cand[k][0];
    c.b = cand[k][1];
    const TetVertices Ta = element(A, c.a), Tb = element(BB, c.b);
    if constexpr (std::is_same_v<R, double>) {
      c.result = fast_record(Ta, Tb, options.variants, &rigid[k]);
    } else {
      c.result = reference::solve_pair(TetPair{"", {}, Ta, Tb}, QpFormulation::Reduced);
    }
    if (options.progress) options.progress(1, hits.size());
  });
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
        o << "element " << i << " of mesh " << which << ": vertex " << v << " (mesh vertex "
          << m.tets[i][v] << ") coordinate " << "xyz"[k] << " is not finite (" << t[v][k] << ")";
        return o.str();
      }
  using P = CGAL::Epick::Point_3;
  auto p = [&](int v) { return P(t[v][0], t[v][1], t[v][2]); };
  if (CGAL::orientation(p(0), p(1), p(2), p(3)) == CGAL::COPLANAR)  // exact predicate
    return "element " + std::to_string(i) + " of mesh " + which +
           " is flat: its four vertices are coplanar (volume 0)";
  return std::nullopt;
}

std::vector<std::array<std::size_t, 2>> box_pairs(const Mesh& A, const std::vector<std::size_t>& ea,
                                                  const Mesh* B, const std::vector<std::size_t>& eb) {
  std::vector<Box> ba(ea.size());
  tbb::parallel_for(std::size_t{0}, ea.size(), [&](std::size_t k) { ba[k] = box_of(A, ea[k]); });
  std::vector<std::array<std::size_t, 2>> out;
  using CGAL::Box_intersection_d::HALF_OPEN;
  // Below `cutoff` boxes CGAL scans instead of recursing. Element boxes of a mesh share many
  // coordinates exactly (neighbours share vertices), and the segment tree's splits degrade on
  // them: on two 72682-element balls (make-meshes.sh --large) the default cutoff 10 took 3.2 s,
  // 1000 took 0.54 s, 10000 0.18 s, 30000 0.16 s; on the small fixtures all take about 1 ms.
  const std::ptrdiff_t cutoff = 10000;
  if (B) {
    std::vector<Box> bb(eb.size());
    tbb::parallel_for(std::size_t{0}, eb.size(), [&](std::size_t k) { bb[k] = box_of(*B, eb[k]); });
    CGAL::box_intersection_d(
        ba.begin(), ba.end(), bb.begin(), bb.end(),
        [&](const Box& x, const Box& y) { out.push_back({x.info(), y.info()}); }, cutoff,
        HALF_OPEN, CGAL::Box_intersection_d::BIPARTITE);
  } else {
    CGAL::box_self_intersection_d(
        ba.begin(), ba.end(),
        [&](const Box& x, const Box& y) {
          out.push_back({std::min(x.info(), y.info()), std::max(x.info(), y.info())});
        },
        cutoff, HALF_OPEN);
  }
  tbb::parallel_sort(out.begin(), out.end());
  return out;
}

unsigned parse_variants(const std::string& list) {
  unsigned v = 0;
  std::stringstream in(list);
  std::string w;
  static const char* names[] = {"rigid", "eq11", "static", "pdd2", "relaxed", "accel1", "accel6"};
  while (std::getline(in, w, ',')) {
    if (w == "all") {
      v |= kAllVariants;
      continue;
    }
    std::size_t k = 0;
    while (k < 7 && w != names[k]) ++k;
    if (k == 7)
      throw std::invalid_argument("unknown variant '" + w +
                                  "' (rigid, eq11, static, pdd2, relaxed, accel1, accel6, all)");
    v |= 1u << k;
  }
  if (!v) throw std::invalid_argument("no variant named");
  return v;
}

std::string variant_names(unsigned variants) {
  static const char* names[] = {"rigid", "eq11", "static", "pdd2", "relaxed", "accel1", "accel6"};
  std::string s;
  for (int k = 0; k < 7; ++k)
    if (variants & (1u << k)) s += (s.empty() ? "" : ",") + std::string(names[k]);
  return s;
}

Contacts<double> contacts(const Mesh& A, const Mesh& B, const ContactOptions& o) { return run<double>(A, &B, o); }
Contacts<double> self_contacts(const Mesh& A, const ContactOptions& o) { return run<double>(A, nullptr, o); }
Contacts<Rational> contacts_exact(const Mesh& A, const Mesh& B, const ContactOptions& o) {
  return run<Rational>(A, &B, o);
}
Contacts<Rational> self_contacts_exact(const Mesh& A, const ContactOptions& o) {
  return run<Rational>(A, nullptr, o);
}

}  // namespace pdd::mesh
