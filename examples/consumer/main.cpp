// The README's library example: one pair through both engines of an installed pdd, then the
// same pair as two one-element meshes through pdd::mesh.
// The pair is fixtures/smoke.json's "poke-vertex-through-face": B's apex pokes 1/2 through A's
// face z = 0; its exact values (fixtures/golden/smoke.jsonl) are PD² = 1/4 and PD_d² = 3/224,
// both along FV:3.
#include <pdd/mesh.h>  // the umbrella: every header of pdd/mesh/ (it includes <pdd/pdd.h>)
#include <pdd/pdd.h>

#include <cmath>
#include <iostream>

int main() {
  pdd::TetPair p{"poke", {}, {{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}}},
                 {{{1, 1, -1}, {3, 1, -1}, {1, 3, -1}, {1.5, 1.5, 0.5}}}};
  pdd::PairResult<double> fast = pdd::fast::solve_pair(p);             // certified doubles
  pdd::PairResult<pdd::Rational> exact = pdd::reference::solve_pair(p);  // exact rationals
  std::cout << "fast:  pdd2 = " << fast.pdd2 << " along " << *fast.pdd2_dir << "\n"
            << "exact: pdd2 = " << exact.pdd2 << " along " << *exact.pdd2_dir << "\n";
  pdd::fast::Depth d = pdd::fast::rigid_pd2(p.A, p.B);  // the hot path: value and label
  std::cout << "rigid: pd2 = " << d.pd2 << " along " << *d.dir << " (exact " << exact.rigid_pd2
            << ")\n";
  pdd::fast::SolveOptions options;  // defaults in pdd.h
  options.gradient = true;
  const pdd::PairResult<double> g = pdd::fast::solve_pair(p, options);
  // Euler's relation for the degree-2 norm: sum_i d_i . d sigma/d d_i = 2 sigma, so the
  // gradient's dot product with the displacements to q1_*_global is -2 pdd2_global.
  double dot = 0;
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k)
      dot += (*g.pdd2_global_grad)[i][k] * ((i < 4 ? g.q1_A_global[i][k] - p.A[i][k]
                                                   : g.q1_B_global[i - 4][k] - p.B[i - 4][k]));
  std::cout << "pdd2_global = " << g.pdd2_global << ", gradient . displacement = " << dot << "\n";
  if (!(std::fabs(dot + 2 * g.pdd2_global) <= 1e-12 * g.pdd2_global)) return 1;
  // definitions §8: the fast value is within 1e-9 relative of the exact one.
  const double e = exact.pdd2.get_d();
  if (!(std::fabs(fast.pdd2 - e) <= 1e-9 * e && fast.pdd2_dir == exact.pdd2_dir)) return 1;

  // The pair as two meshes of one tetrahedron each: one contact, element 0 of A with element 0
  // of B, whose record is the fast engine's (the same solve_pair); A alone has no self-contact
  // (a single element has no partner).
  pdd::mesh::Mesh A, B;
  A.vertices.assign(p.A.begin(), p.A.end());
  B.vertices.assign(p.B.begin(), p.B.end());
  A.tets = B.tets = {{0, 1, 2, 3}};
  const pdd::mesh::Contacts<double> c = pdd::mesh::contacts(A, B);
  const pdd::mesh::Contacts<double> self = pdd::mesh::contacts_self(A);  // self-contact: the _self twin
  std::cout << "mesh:  " << c.pairs.size() << " pair, pdd2 = " << c.pairs.at(0).result.pdd2
            << "; self-contact of A: " << self.pairs.size() << " pairs\n";
  return c.pairs.size() == 1 && c.pairs[0].result.pdd2 == fast.pdd2 && self.pairs.empty() ? 0 : 1;
}
