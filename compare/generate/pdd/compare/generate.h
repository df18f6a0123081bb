// generate.h — reproducible fixture families (`pdd generate --family NAME --seed S --count N`).
//
// Every family is a deterministic function of (seed, count): the random source is
// std::mt19937_64 (its output sequence is fixed by the C++ standard) turned into doubles by
// bit manipulation only, so a family regenerates byte for byte on any conforming platform.
// Degenerate families place coordinates on a dyadic grid, so that the degeneracy they are
// named after (parallel or colinear edges, coplanar faces, touching) holds exactly in the
// doubles, and every property a family promises is checked with the exact engine before a
// pair is kept (intersection: the fast engine's certified filter, the exact Minkowski difference
// where it cannot tell). Closed-form families record their exact expected values as tags
// "key=value" (e.g. "rigid_pd2=1/4"), checked by the tests.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "pdd/tet_pair.h"

namespace pdd::compare {

struct FamilyInfo {
  std::string name;
  std::string description;
};

// The families, in a fixed order.
const std::vector<FamilyInfo>& fixture_families();

// Parameters of the paper's random protocol (definitions §7). Volumes outside [min_volume,
// max_volume] are redrawn: the paper reports volumes "from 0.1 to 130".
struct PaperProtocol {
  double cube_side = 10.0;
  double min_volume = 0.1;
  double max_volume = 130.0;
};

// `count` pairs of `family`, named "<family>-<seed>-<k>". Throws std::invalid_argument for an
// unknown family.
std::vector<TetPair> generate_family(const std::string& family, std::uint64_t seed,
                                     std::size_t count, const PaperProtocol& protocol = {});
// The same pairs handed to `sink` one at a time, in order, as they are made (memory does not
// grow with `count`); the sink returns false to stop.
void generate_family(const std::string& family, std::uint64_t seed, std::size_t count,
                     const PaperProtocol& protocol, const std::function<bool(TetPair&&)>& sink);

// |volume| of a tetrahedron in double precision (the protocol's filter, volume statistics).
double tetrahedron_volume(const TetVertices& t);

// Expected exact values recorded in a pair's tags ("key=value"); empty when none.
std::vector<std::pair<std::string, std::string>> tag_expectations(const TetPair& pair);

}  // namespace pdd::compare
