// record_text.h — a definitions §6 record as a row for people (an aligned table) or for
// spreadsheets (CSV), from the same JSON record that `pdd solve` writes as JSON Lines.
//
// Input : a record (result_json.h: exact values as "p/q" strings, fast values as numbers).
// Output: one line, no newline. Columns: name, intersecting, the seven values, pdd2_global,
//         the four labels, error (the first of `error` and `pdd2_global_error`). Values are
//         decimals: a double in the shortest form that reads back to the same double; an exact
//         rational correctly rounded to 17 significant digits (half to even), marked with a
//         leading '~' in the table where the decimal is not the exact value (CSV cells stay
//         plain numbers). Null values and labels are empty.
// Written by hand: the rounding of a rational to a decimal is a few lines of GMP integer
// arithmetic; no library in Debian's list does it for mpq.
#pragma once

#include <string>

#include "pdd/io/result_json.h"

namespace pdd::io {

enum class RecordFormat { Jsonl, Table, Csv };

// The column names (table: aligned to the rows; CSV: the header row).
std::string record_header(RecordFormat format);
// One record as a row (JSON Lines: the record itself).
std::string record_row(const Json& record, RecordFormat format);

// "p/q" or "p" (lowest terms or not) correctly rounded to 17 significant digits; `exact` set to
// whether the decimal equals the rational. "0" for zero.
std::string decimal17(const std::string& rational, bool* exact = nullptr);

}  // namespace pdd::io
