// io.cpp — pdd.read_fixtures: a fixture file through pdd::io's reader (the one `pdd solve`
// uses, so messages are the CLI's).
#include <pybind11/pybind11.h>

#include <string>

#include "common.h"
#include "pdd/io/fixture_io.h"

namespace pdd_python {
namespace {

py::list read_fixtures(py::handle path_like) {
  const std::string path = path_arg(path_like);
  pdd::io::FixtureFile file;
  {
    py::gil_scoped_release release;
    file = pdd::io::read_fixture_file(path);
  }
  if (file.error) value_error(*file.error);
  py::list out;
  for (const auto& e : file.entries) {
    py::dict d;
    d["name"] = e.pair.name;
    py::list tags;
    for (const auto& t : e.pair.tags) tags.append(py::str(t));
    d["tags"] = tags;
    auto tet = [&](const pdd::TetVertices& t) -> py::object {
      if (e.error) return py::none();
      py::list rows;
      for (const auto& v : t) {
        py::list row;
        for (double c : v) row.append(py::float_(c));
        rows.append(row);
      }
      return rows;
    };
    d["A"] = tet(e.pair.A);
    d["B"] = tet(e.pair.B);
    d["error"] = e.error ? py::object(py::str(*e.error)) : py::object(py::none());
    out.append(d);
  }
  return out;
}

constexpr const char* kReadFixturesDoc = R"doc(read_fixtures(path)
--

A fixture file -> list of dicts: the pairs of a fixture file (docs/definitions.md §1;
fixtures/*.json), read by the same reader as `pdd solve`:
   {"pairs": [{"name": ..., "tags": [...], "A": [[x,y,z] x 4], "B": ...}, ...]}.

Returns one dict per entry, in file order:
  {"name": str, "tags": [str, ...], "A": 4 x [x, y, z] floats, "B": ..., "error": None}
so that solve(p["A"], p["B"], name=p["name"]) solves it. A malformed entry (a missing or
mistyped field, a wrong shape) does not stop the file: it has "error" set to the message
`pdd solve` gives for it, A and B None, and name "#<index>" when it has no usable name.
Non-finite coordinates (1e999) are read as +-inf: solve() then reports them.

A file that cannot be read at all (missing, a directory, empty, not JSON, malformed numbers,
a NUL byte, a repeated key, no "pairs" array) raises ValueError with the message `pdd solve`
prints after "pdd solve: ", e.g. "malformed JSON at byte 12: ...".

  >>> import pdd
  >>> pairs = pdd.read_fixtures("fixtures/smoke.json")
  >>> len(pairs), pairs[0]["name"], pairs[0]["tags"], pairs[0]["A"][1], pairs[0]["error"]
  (6, 'nested-1', ['nested'], [10.0, 0.0, 0.0], None)
  >>> pdd.solve(pairs[0]["A"], pairs[0]["B"], engine="reference")["rigid_pd2"]
  Fraction(16, 3)
)doc";

}  // namespace

void bind_io(py::module_& m) {
  m.def("read_fixtures", &read_fixtures, kReadFixturesDoc, py::arg("path"));
}

}  // namespace pdd_python
