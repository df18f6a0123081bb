// mesh/variants.h — which values contacts() computes per pair: one bit per definitions §6 value,
// their names (the CLI's --variants, Python's variants=) and keys.
//
// Inputs   a comma-separated list of names (parse_variants) or a set of Variant bits.
// Outputs  the bits (parse_variants), the names (variant_names), a record's value of one
//          variant (variant_value).
//
// Bit k < kValueCount is the value kValueKeys[k] of pair_result.h, bit kValueCount (kGlobal)
// definitions §9's pdd2_global and its keys. kDefaultVariants is the default of
// ContactOptions::variants, `pdd mesh --variants` and Python's mesh_contacts(variants=).
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "pdd/pdd.h"

namespace pdd::mesh {

enum Variant : unsigned {
  kRigid = 1u << 0,    // rigid_pd2 (+ rigid_dir)
  kEq11 = 1u << 1,     // eq11_pd2
  kStatic = 1u << 2,   // pdd2_static (+ pdd2_static_dir)
  kPdd2 = 1u << 3,     // pdd2 (+ pdd2_dir, q1_A, q1_B)
  kRelaxed = 1u << 4,  // pdd2_relaxed (+ pdd2_relaxed_dir)
  kAccel1 = 1u << 5,   // pdd2_accel1
  kAccel6 = 1u << 6,   // pdd2_accel6
  kGlobal = 1u << 7,   // pdd2_global (+ pdd2_global_normal, q1_A_global, q1_B_global and,
                       // reference engine, pdd2_global_lower); see "kGlobal" in contacts.h
};
inline constexpr std::size_t kVariantCount = kValueCount + 1;
inline constexpr unsigned kAllVariants = (1u << kVariantCount) - 1;
inline constexpr unsigned kDefaultVariants = kRigid | kStatic | kPdd2 | kAccel1;
static_assert(kGlobal == 1u << kValueCount, "bit k of a variant set is the value kVariantKeys[k]");
// Variant k's name (--variants) and the key of its value in the record.
inline constexpr std::array<const char*, kVariantCount> kVariantNames = {
    "rigid", "eq11", "static", "pdd2", "relaxed", "accel1", "accel6", "global"};
inline constexpr std::array<const char*, kVariantCount> kVariantKeys = {
    kValueKeys[0], kValueKeys[1], kValueKeys[2], kValueKeys[3],
    kValueKeys[4], kValueKeys[5], kValueKeys[6], "pdd2_global"};
// The value of variant k (kVariantKeys[k]) in a record.
template <class R>
const R& variant_value(const PairResult<R>& r, std::size_t k) {
  return k < kValueCount ? record_value(r, k) : r.pdd2_global;
}
// "rigid,static,pdd2,accel1" (names: rigid eq11 static pdd2 relaxed accel1 accel6 global, or
// "all": every one) -> bits; throws std::invalid_argument naming the unknown word.
unsigned parse_variants(const std::string& list);
std::string variant_names(unsigned variants);  // the inverse, comma-separated

}  // namespace pdd::mesh
