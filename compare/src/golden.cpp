#include "pdd/compare/golden.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pdd/compare/engines.h"
#include "pdd/compare/output.h"
#include "pdd/compare/result_json.h"

namespace pdd::compare {
namespace fs = std::filesystem;

std::vector<std::string> golden_fixture_files(const std::string& fixtures_dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(fixtures_dir)) {
    if (!e.is_regular_file() || e.path().extension() != ".json") continue;
    const std::string rel = fs::relative(e.path(), fixtures_dir).generic_string();
    if (rel.rfind("bad/", 0) == 0 || rel.rfind("golden/", 0) == 0) continue;
    out.push_back(rel);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string golden_path(const std::string& fixtures_dir, const std::string& relative) {
  return (fs::path(fixtures_dir) / "golden" / fs::path(relative).replace_extension(".jsonl"))
      .generic_string();
}

std::string exact_json_lines(const std::string& fixture_path, QpFormulation f) {
  const FixtureFile file = read_fixture_file(fixture_path);
  if (file.error) throw std::runtime_error(*file.error);
  std::string out;
  for (const auto& r : run_reference(file.entries, {f}, false)) out += exact_record(r).dump() + "\n";
  return out;
}

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The first line that differs, both versions, for the report.
std::string first_difference(const std::string& want, const std::string& got) {
  std::istringstream a(want), b(got);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ha = bool(std::getline(a, la)), hb = bool(std::getline(b, lb));
    if (!ha && !hb) return "identical";
    if (la != lb || ha != hb)
      return "line " + std::to_string(line) + "\n  golden: " + (ha ? la : "<none>") +
             "\n  now:    " + (hb ? lb : "<none>");
  }
}

}  // namespace

std::vector<GoldenMismatch> check_golden(const std::string& fixtures_dir, QpFormulation f) {
  std::vector<GoldenMismatch> out;
  for (const auto& rel : golden_fixture_files(fixtures_dir)) {
    const std::string gpath = golden_path(fixtures_dir, rel);
    if (!fs::exists(gpath)) {
      out.push_back({rel, "no golden file " + gpath + " (run pdd golden --update)"});
      continue;
    }
    const std::string want = read_text(gpath);
    const std::string got = exact_json_lines((fs::path(fixtures_dir) / rel).string(), f);
    if (want != got) out.push_back({rel, first_difference(want, got)});
  }
  return out;
}

namespace {

reference::Rational rational(const Json& j) { return reference::Rational(j.get<std::string>()); }

std::optional<DirectionLabel> label(const Json& j) {
  if (j.is_null()) return std::nullopt;
  auto l = DirectionLabel::parse(j.get<std::string>());
  if (!l) throw std::runtime_error("bad label " + j.dump());
  return l;
}

Positions<reference::Rational> positions(const Json& j) {
  Positions<reference::Rational> q;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) q[i][k] = rational(j.at(i).at(k));
  return q;
}

reference::ExactResult exact_result_from_json(const Json& j) {
  reference::ExactResult r;
  r.name = j.at("name").get<std::string>();
  if (!j.at("error").is_null()) {
    r.error = j.at("error").get<std::string>();
    return r;
  }
  r.intersecting = j.at("intersecting").get<bool>();
  r.rigid_pd2 = rational(j.at("rigid_pd2"));
  r.eq11_pd2 = rational(j.at("eq11_pd2"));
  r.pdd2_static = rational(j.at("pdd2_static"));
  r.pdd2 = rational(j.at("pdd2"));
  r.pdd2_relaxed = rational(j.at("pdd2_relaxed"));
  r.pdd2_accel1 = rational(j.at("pdd2_accel1"));
  r.pdd2_accel6 = rational(j.at("pdd2_accel6"));
  r.rigid_dir = label(j.at("rigid_dir"));
  r.pdd2_static_dir = label(j.at("pdd2_static_dir"));
  r.pdd2_dir = label(j.at("pdd2_dir"));
  r.pdd2_relaxed_dir = label(j.at("pdd2_relaxed_dir"));
  r.q1_A = positions(j.at("q1_A"));
  r.q1_B = positions(j.at("q1_B"));
  return r;
}

}  // namespace

std::vector<reference::ExactResult> read_golden(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<reference::ExactResult> out;
  for (std::string line; std::getline(in, line);) {
    try {
      out.push_back(exact_result_from_json(Json::parse(line)));
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ": " + e.what());
    }
  }
  return out;
}

std::vector<std::string> update_golden(const std::string& fixtures_dir, QpFormulation f) {
  std::vector<std::string> written;
  for (const auto& rel : golden_fixture_files(fixtures_dir)) {
    const std::string gpath = golden_path(fixtures_dir, rel);
    fs::create_directories(fs::path(gpath).parent_path());
    if (auto why = write_file(gpath, exact_json_lines((fs::path(fixtures_dir) / rel).string(), f)))
      throw std::runtime_error(*why);
    written.push_back(rel);
  }
  return written;
}

}  // namespace pdd::compare
