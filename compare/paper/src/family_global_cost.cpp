#include "pdd/compare/family_global_cost.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "pdd/compare/golden.h"
#include "pdd/io/fixture_io.h"
#include "pdd/io/golden_files.h"
#include "pdd/pdd.h"
#include "pdd/reference/candidate_directions.h"

namespace pdd::compare {
using io::FixtureEntry;
using io::FixtureFile;
using io::golden_path;
using io::read_fixture_file;

std::vector<std::array<double, 3>> candidate_normals_rounded(const TetPair& pair) {
  std::vector<std::array<double, 3>> out;
  for (const auto& d : reference::candidate_directions(reference::to_exact(pair))) {
    const reference::Rational c[3] = {d.n.x(), d.n.y(), d.n.z()};
    std::array<double, 3> v = {CGAL::to_double(c[0]), CGAL::to_double(c[1]), CGAL::to_double(c[2])};
    const double m = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
    if (!(m >= 0x1p-900 && m <= 0x1p900)) {
      // A cross product of a pair scaled by 2^+-450 overflows or underflows a double: divide
      // by its largest component exactly first, so that the direction survives the rounding.
      int k = 0;
      for (int i = 1; i < 3; ++i)
        if (CGAL::abs(c[i]) > CGAL::abs(c[k])) k = i;
      if (CGAL::is_zero(c[k])) continue;
      const reference::Rational big = CGAL::abs(c[k]);
      for (int i = 0; i < 3; ++i) v[i] = CGAL::to_double(c[i] / big);
    }
    out.push_back(v);
  }
  return out;
}

std::vector<FamilyGlobalCost> family_global_costs(const std::string& fixtures_dir) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(fixtures_dir) / "families";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error("no folder " + dir.string());
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());

  std::vector<FamilyGlobalCost> out;
  for (const fs::path& file : files) {
    const FixtureFile fixture = read_fixture_file(file.string());
    if (fixture.error) throw std::runtime_error(file.string() + ": " + *fixture.error);
    std::vector<TetPair> pairs;
    for (const FixtureEntry& e : fixture.entries) {
      if (e.error) throw std::runtime_error(file.string() + ": pair '" + e.pair.name + "': " + *e.error);
      pairs.push_back(e.pair);
    }
    const std::string golden = golden_path(fixtures_dir, "families/" + file.filename().string());
    const std::vector<reference::ExactResult> exact = read_golden(golden);
    if (exact.size() != pairs.size())
      throw std::runtime_error(golden + " has " + std::to_string(exact.size()) + " records for " +
                               std::to_string(pairs.size()) + " pairs in " + file.string());
    FamilyGlobalCost c;
    c.family = file.stem().string();
    c.pairs = pairs.size();
    for (const auto& r : exact) c.intersecting += (!r.error && r.intersecting);
    c.fast = global_statistics(pairs, fast::solve_batch(pairs), [](double x) { return x; },
                               candidate_normals_rounded);
    c.exact = global_statistics(pairs, exact, [](const reference::Rational& q) { return CGAL::to_double(q); },
                                candidate_normals_rounded);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace pdd::compare
