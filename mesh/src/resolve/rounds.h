// rounds.h — the rounds of resolve (resolve.h): from the current positions, each round finds the
// contacts afresh, projects every intersecting pair (local step, local_step.h), moves the
// vertices (the elastic global step, or the per-pair combination) and limits the step so that R2
// and R4 hold (step_limit.h).
//
// Inputs:  the run (its sides at the current positions), a budget of rounds.
// Outputs: the sides moved, one ResolveRound per round in run.rep; returns true when a contact
//          stage found no pair (R1 at the positions reached), false when the rounds stalled,
//          the budget ended or no pair had a solution (then rep.stopped_because says so).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "state.h"

namespace pdd::mesh::detail {

// The contact stage (timed into rep.seconds_contacts): every intersecting pair at the current
// positions (the set intersecting_pairs gives): self-contact from the run's candidate list
// (contact_list.h), two meshes by intersecting_pairs itself.
std::vector<std::array<std::size_t, 2>> contacts(Run& run);

// The projective-dynamics rounds: half-space targets (plane_targets; along one direction per
// disagreeing contact patch, patch_direction.h), the elastic global step (elastic_step.h) and
// the step limit. They stall after kStallRounds rounds without fewer pairs
// than the best round; with OnFewPairs::Exit (two meshes) also after kFewPairsRounds rounds
// without fewer pairs when kFewPairs or fewer are left (the per-pair rounds finish those:
// resolve.cpp); with OnSlowDecay::Exit (two meshes' first rounds) also when the count falls too
// slowly to get there within the budget (decays_too_slowly).
enum class OnFewPairs { Exit, Continue };
enum class OnSlowDecay { Exit, Continue };
constexpr std::size_t kFewPairs = 16;
// The per-pair rounds that finish projective-dynamics rounds stalled on kFewPairs pairs or
// fewer (resolve.cpp's first fallback, and each step of the walk back towards rest: fallbacks.h).
constexpr std::size_t kFinishRounds = 10;
bool run_pd_rounds(Run& run, std::size_t budget, OnFewPairs on_few = OnFewPairs::Continue,
                   OnSlowDecay on_slow = OnSlowDecay::Continue);
// The slow decay of two meshes' rounds: counts[r] the pairs found at the start of round r (the
// last one about to be run); true when, past the first rounds, the count falls so slowly that at
// its rate over the last rounds it would not reach kFewPairs within `budget` rounds
// (rounds.cpp: the rate, its window, the cases).
bool decays_too_slowly(const std::vector<std::size_t>& counts, std::size_t budget);

// Whether the per-pair rounds end when they stall (the first try after the projective-dynamics
// rounds) or use the whole budget (the rounds of the fallbacks).
enum class OnStall { Exit, Continue };

// The per-pair rounds: each free vertex moves by the variant's rule (round_rule: the longest or
// the volume-weighted mean of its pairs' moves, finish_move, times the overshoot), step limit
// as above.
bool run_pair_rounds(Run& run, std::size_t budget, ResolveVariant variant, OnStall on_stall);

}  // namespace pdd::mesh::detail
