// record_line.h — a definitions §6 record as its JSON Lines text, written directly: the bytes
// of asked_keys(result_json(r, number), variants).dump() (result_json.h), without the JSON object.
//
// Input : a record of either engine (fast: doubles, written as JSON numbers; exact: rationals,
//         as "p/q" strings, the writers of `pdd solve` and `pdd mesh`), the variants asked
//         (asked_key: bit k < kValueCount the value kValueKeys[k], bit kValueCount §9's keys;
//         ~0u: every key), and for a mesh contact the element pair (a, b), written first in
//         place of the name (definitions §10).
// Output: one line, no newline.
// Written by hand over emit_record's keys: building, filtering, copying and freeing an
// ordered_json per record takes more than half of `pdd mesh`'s time (79,004 contacts of two 10³
// Kuhn grids, one rotated, one thread: 1.64 s through the objects, 0.72 s written directly; the
// same contacts without records, in Python, 0.42 s). The text is still nlohmann's: numbers in
// its shortest round-trip form (detail::to_chars, which dump() calls; null where not finite),
// strings through its escaping where they need any.
#pragma once

#include <cstddef>
#include <string>

#include "pdd/io/result_json.h"
#include "pdd/pdd.h"

namespace pdd::io {

std::string record_line(const PairResult<double>& r, unsigned variants = ~0u);
std::string record_line(const PairResult<Rational>& r, unsigned variants = ~0u);
// {"a": a, "b": b, then the record's keys but its name}: `pdd mesh`'s line of one contact.
std::string contact_line(std::size_t a, std::size_t b, const PairResult<double>& r, unsigned variants);
std::string contact_line(std::size_t a, std::size_t b, const PairResult<Rational>& r, unsigned variants);

}  // namespace pdd::io
