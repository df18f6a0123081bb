#include "pdd/io/golden_files.h"

#include <algorithm>
#include <filesystem>

namespace pdd::io {
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

}  // namespace pdd::io
