// contact_list.h — the contact stage of the rounds (rounds.h): every intersecting element pair
// at the current positions, the same set as intersecting_pairs (resolve.h), from a candidate
// list kept over the rounds instead of a fresh broadphase each round.
//
// Inputs:  the meshes at their current positions (A, and B; none for self-contact) and their
//          valid elements, once per round.
// Outputs: the pairs (a, b) whose interiors intersect (exact decision), sorted; self-contact:
//          a < b sharing no vertex.
// The candidate list (a Verlet list): at a build, the box pairs of the elements' boxes grown
// by g on every side (grown_box_pairs). While no vertex coordinate is more than g/2 from where
// it was at the build, every element's box lies inside its grown box (argued at kGrowShare),
// so every pair of such elements whose boxes overlap, every intersecting pair among them, is a
// candidate. An element with a vertex further away (escaped) is paired afresh each round by box
// intersection with all elements at the current positions; when many have escaped, the list is
// rebuilt. Each round decides exactly (fast::interiors_intersect) only the candidates with an
// element whose vertices changed since the last round; the others keep their last decision
// (same doubles, same exact answer).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "pdd/mesh.h"

namespace pdd::mesh::detail {

class ContactList {
 public:
  using Pair = std::array<std::size_t, 2>;
  // The intersecting pairs of (a, ea) with (b, eb) (b null: a with itself) at their positions.
  std::vector<Pair> pairs(const Mesh& a, const std::vector<std::size_t>& ea, const Mesh* b,
                          const std::vector<std::size_t>& eb);
  std::size_t builds() const { return builds_; }

 private:
  struct Seen {
    const Mesh* mesh = nullptr;
    std::vector<std::size_t> elems;
    std::vector<Vec3d> built, last;  // the positions at the build and at the last call
    std::vector<char> changed;       // per element: a vertex differs from `last`
    std::vector<char> escaped;       // per element: a vertex further than g/2 from `built`
  };
  bool same_input(const Mesh& a, const std::vector<std::size_t>& ea, const Mesh* b,
                  const std::vector<std::size_t>& eb) const;
  void build(const Mesh& a, const std::vector<std::size_t>& ea, const Mesh* b, const std::vector<std::size_t>& eb);
  std::vector<Pair> escaped_pairs(const Mesh& a, const Mesh* b) const;
  Seen sa_, sb_;
  bool self_ = true, valid_ = false;
  double grow_ = 0;
  std::vector<Pair> candidates_;  // the pairs of grown boxes at the build
  std::vector<char> hit_;         // per candidate: its last exact decision
  std::vector<std::array<double, 6>> box_a_, box_b_;  // per element: its box (lo, hi) this round
  std::size_t builds_ = 0;
};

}  // namespace pdd::mesh::detail
