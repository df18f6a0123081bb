// fuzz_fixture_reader — arbitrary bytes into the fixture reader (io/pdd/io/fixture_io.h,
// public functions only). Input format: the bytes of a fixture file, as `pdd` would read them.
//
// Must hold for every input (a violation aborts, which libFuzzer and the replay test report):
//   - parse_fixture_text returns (no crash, no sanitizer report, no exception escapes);
//   - a file-level error and entries do not come together (the header: the error is "set when
//     nothing could be read");
//   - round trip (header: "round-trip exact"): the pairs read without error and with finite
//     coordinates, written by fixture_json and read again, come back as the same pairs, bit for
//     bit (names, tags, every double including the sign of zero), without errors.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "pdd/io/fixture_io.h"

namespace {

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_fixture_reader: %s\n%s\n", what, detail.c_str());
  std::abort();
}

bool finite_pair(const pdd::TetPair& p) {
  for (const auto* tet : {&p.A, &p.B})
    for (const auto& v : *tet)
      for (double x : v)
        if (!std::isfinite(x)) return false;
  return true;
}

bool same_bits(const pdd::TetVertices& a, const pdd::TetVertices& b) {
  return std::memcmp(a.data(), b.data(), sizeof(pdd::TetVertices)) == 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const pdd::io::FixtureFile file = pdd::io::parse_fixture_text(text);
  if (file.error && !file.entries.empty()) fail("file error together with entries", *file.error);

  std::vector<pdd::TetPair> good;
  for (const auto& e : file.entries)
    if (!e.error && finite_pair(e.pair)) good.push_back(e.pair);
  if (good.empty()) return 0;

  const std::string written = pdd::io::fixture_json(good);
  const pdd::io::FixtureFile again = pdd::io::parse_fixture_text(written);
  if (again.error) fail("fixture_json output does not read back", *again.error + "\n" + written);
  if (again.entries.size() != good.size()) fail("round trip changed the number of pairs", written);
  for (size_t i = 0; i < good.size(); ++i) {
    const auto& e = again.entries[i];
    if (e.error) fail("round trip: a written pair reads back as an error", *e.error + "\n" + written);
    if (e.pair.name != good[i].name) fail("round trip changed a name", written);
    if (e.pair.tags != good[i].tags) fail("round trip changed tags", written);
    if (!same_bits(e.pair.A, good[i].A) || !same_bits(e.pair.B, good[i].B))
      fail("round trip changed a coordinate", written);
  }
  return 0;
}
