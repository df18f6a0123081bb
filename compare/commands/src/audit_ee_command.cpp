#include <iomanip>
#include <iostream>
#include <memory>

#include "pdd/cli/exit_codes.h"
#include "pdd/compare/edge_audit.h"
#include "pdd/compare/engines.h"
#include "pdd/compare/research_commands.h"
#include "pdd/io/fixture_io.h"
#include "pdd/io/output.h"
#include "pdd/io/result_json.h"

namespace pdd::compare {
using io::FixtureFile;
using io::Json;
using io::read_fixture_file;
namespace {

struct AuditArgs {
  std::string input;
  bool json = false;
};

Json pairs_json(const std::vector<std::array<int, 2>>& v) {
  Json a = Json::array();
  for (const auto& ab : v) a.push_back(Json::array({ab[0], ab[1]}));
  return a;
}
Json flags_json(const CaseFlags& f) {
  return Json{{"static", f.static_case}, {"deformable", f.deformable}, {"relaxed", f.relaxed}};
}

Json audit_json(const EdgeAudit& a) {
  Json j;
  j["name"] = a.name;
  if (a.error) {
    j["error"] = *a.error;
    return j;
  }
  j["intersecting"] = a.intersecting;
  j["parallel"] = pairs_json(a.parallel);
  j["colinear"] = pairs_json(a.colinear);
  j["undecidable"] = pairs_json(a.undecidable);
  j["decided_checked"] = a.decided_checked;
  j["discarded_smaller_deformable"] = a.discarded_smaller_deformable;
  j["discarded_smaller_relaxed"] = a.discarded_smaller_relaxed;
  j["discarded_feasible_static"] = a.discarded_feasible_static;
  j["discarded_changes_result"] = flags_json(a.discarded_changes_result);
  j["colinear_directions"] = a.colinear_directions;
  j["colinear_changes_result"] = flags_json(a.colinear_changes_result);
  j["optimum_parallel"] = flags_json(a.optimum_parallel);
  j["optimum_undecidable"] = flags_json(a.optimum_undecidable);
  j["error"] = nullptr;
  return j;
}

// Counts of pairs per case (static / deformable / relaxed).
struct CaseCount {
  std::size_t s = 0, d = 0, r = 0;
  void add(const CaseFlags& f) { s += f.static_case, d += f.deformable, r += f.relaxed; }
};
std::ostream& operator<<(std::ostream& o, const CaseCount& c) {
  return o << c.s << " / " << c.d << " / " << c.r;
}

int run_audit(const AuditArgs& a) {
  const FixtureFile file = read_fixture_file(a.input);
  if (file.error) {
    std::cerr << "pdd audit-ee: " << *file.error << "\n";
    return kExitFileError;
  }
  const auto out = map_entries<EdgeAudit>(file.entries, "pdd audit-ee", true,
                                          [](const TetPair& pair, std::size_t) { return edge_audit(pair); });

  std::size_t audited = 0, rejected = 0, with_par = 0, n_par = 0, with_col = 0, n_col = 0,
              with_und = 0, n_und = 0, decided = 0, smaller_d = 0, smaller_r = 0, feas_s = 0,
              pairs_smaller_d = 0, col_dirs = 0;
  CaseCount disc_changes, col_changes, opt_par, opt_und;
  for (const auto& r : out) {
    if (a.json) std::cout << audit_json(r).dump() << "\n";
    if (r.error) {
      ++rejected;
      std::cerr << "pdd audit-ee: pair '" << printable(r.name) << "' rejected: " << *r.error << "\n";
      continue;
    }
    if (!r.intersecting) continue;
    ++audited;
    with_par += !r.parallel.empty(), n_par += r.parallel.size();
    with_col += !r.colinear.empty(), n_col += r.colinear.size();
    with_und += !r.undecidable.empty(), n_und += r.undecidable.size();
    decided += r.decided_checked, smaller_d += r.discarded_smaller_deformable;
    smaller_r += r.discarded_smaller_relaxed, feas_s += r.discarded_feasible_static;
    pairs_smaller_d += r.discarded_smaller_deformable > 0;
    disc_changes.add(r.discarded_changes_result);
    col_dirs += r.colinear_directions;
    col_changes.add(r.colinear_changes_result);
    opt_par.add(r.optimum_parallel);
    opt_und.add(r.optimum_undecidable);
  }
  std::ostream& s = a.json ? std::cerr : std::cout;
  s << "Edge-edge audit, exactly, on " << audited << " intersecting pairs (counts per case: static / deformable / relaxed)\n"
    << "  parallel edge pairs:     " << n_par << " in " << with_par << " pairs\n"
    << "  colinear edge pairs:     " << n_col << " in " << with_col << " pairs\n"
    << "  undecidable edge pairs:  " << n_und << " in " << with_und << " pairs\n"
    << "  orientation rule: " << decided << " decided EE directions re-solved with -n\n"
    << "    -n has the smaller case-2 optimum:   " << smaller_d << " directions, in " << pairs_smaller_d << " pairs\n"
    << "    -n has the smaller relaxed optimum:  " << smaller_r << " directions\n"
    << "    -n feasible in case 1:               " << feas_s << " directions\n"
    << "    -n would lower the pair's result:    " << disc_changes << " pairs\n"
    << "  colinear pairs: " << col_dirs << " incident-face directions solved\n"
    << "    would lower the pair's result:       " << col_changes << " pairs\n"
    << "  optimum is a parallel EE direction:    " << opt_par << " pairs\n"
    << "  optimum is an undecidable EE direction: " << opt_und << " pairs\n";
  return rejected ? kExitPairRejected : kExitOk;
}

}  // namespace

void add_audit_ee_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<AuditArgs>();
  CLI::App* cmd = app.add_subcommand(
      "audit-ee", "Audit parallel, colinear and undecidable edge pairs and the EE orientation rule, exactly.");
  cmd->add_option("--input", a->input, "Fixture file")->required();
  cmd->add_flag("--json", a->json, "Write one JSON object per pair to standard output (summary to stderr)");
  cmd->callback([a, &exit_code] { exit_code = run_audit(*a); });
}

}  // namespace pdd::compare
