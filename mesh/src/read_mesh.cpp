// read_mesh.cpp — Gmsh MSH (2.2 and 4.1, ASCII and binary) and legacy VTK unstructured grid
// readers (definitions §10), written by hand.
//
// Why not Gmsh's own reader (Debian's libgmsh-dev, the Gmsh SDK): it is GPL, and linking it
// would make the pdd library and tool GPL too; it keeps one global model behind
// gmsh::initialize/finalize (not reentrant, not thread-safe, prints to the terminal); and its
// messages do not name the line or the element of a bad file, which definitions §10 asks for. It
// does not read legacy VTK into tetrahedra either. The formats read here are small and documented
// (Gmsh reference manual, "MSH file format"; VTK "File Formats", legacy section). The readers
// are tested against files Gmsh 4.8.4 wrote (scripts/make-meshes.sh, fixtures/meshes/: the
// same ball in all six encodings must read to the same tetrahedra) and against hand-made bad
// files. Only what pdd needs is interpreted: nodes and tetrahedra; every other section
// ($Entities, $PhysicalNames, $NodeData, CELL_DATA, ...) is skipped.
//
// Errors are ReadError("PATH:LINE: message") in text, "PATH: byte N: message" in binary data.
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>

#include "pdd/mesh.h"
#include "pdd/printable.h"

namespace pdd::mesh {
namespace {

class Cursor {
 public:
  Cursor(std::string path, std::string data) : path_(std::move(path)), s_(std::move(data)) {}

  [[noreturn]] void fail(const std::string& msg, std::size_t at, bool binary = false) const {
    std::ostringstream o;
    if (binary) {
      o << path_ << ": byte " << at << ": " << msg;
    } else {
      const std::size_t line = 1 + std::count(s_.begin(), s_.begin() + std::min(at, s_.size()), '\n');
      o << path_ << ":" << line << ": " << msg;
    }
    throw ReadError(printable(o.str()));  // the file's control characters as \xNN
  }
  [[noreturn]] void fail(const std::string& msg) const { fail(msg, pos_); }

  // Where offset `at` is, for a vertex's message: "PATH:LINE" in text, "PATH, byte N" in binary
  // data. Lines are counted on from the previous call's offset when `at` lies after it (the
  // readers ask in file order), so a file of many non-finite vertices is still read in linear time.
  std::string location(std::size_t at, bool binary) {
    at = std::min(at, s_.size());
    if (binary) return printable(path_ + ", byte " + std::to_string(at));
    if (at < counted_to_) counted_to_ = 0, counted_lines_ = 1;
    counted_lines_ += std::count(s_.begin() + counted_to_, s_.begin() + at, '\n');
    counted_to_ = at;
    return printable(path_ + ":" + std::to_string(counted_lines_));
  }

  bool at_end() {
    skip_space();
    return pos_ >= s_.size();
  }
  std::size_t pos() const { return pos_; }
  void set_pos(std::size_t p) { pos_ = p; }
  const std::string& data() const { return s_; }

  void skip_space() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r' ||
                                s_[pos_] == '\n'))
      ++pos_;
  }
  // Spaces and tabs only: stays on the line.
  void skip_blank() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
  }
  bool at_line_end() {
    skip_blank();
    return pos_ >= s_.size() || s_[pos_] == '\n';
  }

  std::string_view word(const char* what) {
    skip_space();
    if (pos_ >= s_.size()) fail(std::string("the file ends where ") + what + " was expected (truncated?)");
    const std::size_t b = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return std::string_view(s_).substr(b, pos_ - b);
  }
  // A word on the current line (the line must not end first).
  std::string_view word_on_line(const char* what) {
    skip_blank();
    if (pos_ >= s_.size()) fail(std::string("the file ends where ") + what + " was expected (truncated?)");
    if (s_[pos_] == '\n') fail(std::string("the line ends where ") + what + " was expected");
    return word(what);
  }
  void expect(std::string_view w) {
    const std::size_t at = (skip_space(), pos_);
    const std::string_view got = word(std::string(w).c_str());
    if (got != w) fail("expected '" + std::string(w) + "', found '" + std::string(got) + "'", at);
  }

  long long integer(const char* what, bool on_line = false) {
    const std::size_t at = (skip_space(), pos_);
    const std::string_view w = on_line ? word_on_line(what) : word(what);
    long long v = 0;
    const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), v);
    if (ec != std::errc() || end != w.data() + w.size())
      fail(std::string(what) + ": '" + std::string(w) + "' is not an integer", at);
    return v;
  }
  long long count(const char* what, bool on_line = false) {
    const std::size_t at = (skip_space(), pos_);
    const long long v = integer(what, on_line);
    if (v < 0 || v > (1ll << 40)) fail(std::string(what) + ": " + std::to_string(v) + " is out of range", at);
    // Every counted item takes at least a byte of the file: a larger count is a lie, and the
    // reader would allocate for it before finding out (a 300-byte file saying "POINTS
    // 1000000000 double" would ask for 24 GB).
    if (static_cast<unsigned long long>(v) > s_.size() - std::min(pos_, s_.size()))
      fail(std::string(what) + ": " + std::to_string(v) + " is more than the " +
               std::to_string(s_.size() - std::min(pos_, s_.size())) + " bytes left in the file",
           at);
    return v;
  }
  // A coordinate: any decimal or "nan"/"inf" (kept as read; the element is reported later).
  double number(const char* what, bool on_line = false) {
    const std::size_t at = (skip_space(), pos_);
    const std::string w(on_line ? word_on_line(what) : word(what));
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (w.empty() || end != w.c_str() + w.size())
      fail(std::string(what) + ": '" + w + "' is not a number", at);
    if (const auto why = inexact_integer(w, v)) fail(std::string(what) + ": " + *why, at);
    return v;
  }
  // The fixture reader's rule (io/fixture_io.cpp), the same for every reader: an integer
  // literal (an optional sign and digits only) must be exactly the double it is read as
  // (9007199254740993 = 2^53 + 1 is not: it would silently become 9007199254740992), and
  // within the double range; a literal with a fraction or an exponent is read as the nearest
  // double, as everywhere. glibc prints a double's exact decimal expansion with "%.0f".
  static std::optional<std::string> inexact_integer(const std::string& w, double v) {
    std::size_t i = (w[0] == '-' || w[0] == '+') ? 1 : 0;
    if (i == w.size() || w.find_first_not_of("0123456789", i) != std::string::npos) return std::nullopt;
    while (i + 1 < w.size() && w[i] == '0') ++i;  // leading zeros
    const std::string shown = w.size() > 60 ? w.substr(0, 60) + "..." : w;
    if (!std::isfinite(v)) return "the integer " + shown + " is beyond the largest double (not finite)";
    char buf[400];
    std::snprintf(buf, sizeof buf, "%.0f", std::fabs(v));
    if (w.compare(i, std::string::npos, buf) == 0) return std::nullopt;
    char nearest[40];
    std::snprintf(nearest, sizeof nearest, "%.17g", v);  // as the fixture reader's message
    return "the integer " + shown + " is not exactly a double (coordinates are doubles; write it as one, e.g. " +
           nearest + ")";
  }
  // The rest of the current line and the newline.
  void next_line() {
    while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
    if (pos_ < s_.size()) ++pos_;
  }

  template <class T>
  T raw(const char* what, bool big_endian = false) {
    if (s_.size() - std::min(pos_, s_.size()) < sizeof(T))
      fail(std::string("the file ends inside the binary data (") + what + "; truncated?)", pos_, true);
    unsigned char b[sizeof(T)];
    std::memcpy(b, s_.data() + pos_, sizeof(T));
    if (big_endian) std::reverse(b, b + sizeof(T));  // the hosts pdd supports are little-endian
    T v;
    std::memcpy(&v, b, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }

 private:
  std::string path_;
  std::string s_;
  std::size_t pos_ = 0;
  std::size_t counted_to_ = 0, counted_lines_ = 1;  // location(): line of offset counted_to_
};

std::string read_file(const std::string& path) {
  // A mesh is a regular file: a directory would read as empty, a device such as /dev/zero
  // would never end.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::is_directory(status)) throw ReadError("'" + path + "' is a directory, not a mesh file");
  if (!ec && !std::filesystem::is_regular_file(status))
    throw ReadError("'" + path + "' is not a regular file (a mesh is read from a file)");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ReadError("cannot read '" + path + "'" + (errno ? std::string(": ") + std::strerror(errno) : ""));
  std::ostringstream o;
  o << in.rdbuf();
  if (in.bad()) throw ReadError("cannot read '" + path + "'");
  return o.str();
}

// A tetrahedron as the file gives it: node tags, resolved to vertex indices at the end (nodes
// and elements may come in any order, and messages name the element and where it was).
struct PendingTet {
  std::array<long long, 4> nodes;
  long long id;       // element tag (MSH) or cell index (VTK)
  std::size_t where;  // offset of its record
  bool binary;
};

// Number of nodes of each Gmsh element type (reference manual, "MSH file format"): needed to
// step over elements in binary files. 0: unknown.
int gmsh_nodes_of_type(long long type) {
  static const int n[] = {0,  2,  3,  4,  4,  8,  6,  5,  3,  6,  9,  10, 27, 18, 14, 1,  8,
                          20, 15, 13, 9,  10, 12, 15, 15, 21, 4,  5,  6,  20, 35, 56, 0,  0,
                          0,  0,  16, 0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0,  0};
  if (type >= 0 && type < static_cast<long long>(sizeof n / sizeof n[0])) return n[type];
  if (type == 92) return 64;
  if (type == 93) return 125;
  return 0;
}
constexpr long long kGmshTet = 4;

struct MshState {
  explicit MshState(Cursor& cursor) : c(cursor) {}
  Cursor& c;
  bool binary = false;
  std::vector<Vec3d> vertices;
  std::map<std::size_t, std::string> sources;  // Mesh::vertex_sources
  std::unordered_map<long long, std::size_t> index_of;
  std::vector<PendingTet> tets;

  void add_node(long long tag, const Vec3d& x, std::size_t where) {
    if (!index_of.emplace(tag, vertices.size()).second)
      c.fail("node " + std::to_string(tag) + " is defined twice", where, binary);
    if (!(std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2])))
      sources.emplace(vertices.size(), "node " + std::to_string(tag) + " at " + c.location(where, binary));
    vertices.push_back(x);
  }
  Vec3d coords_text() {
    Vec3d x;
    for (int k = 0; k < 3; ++k) x[k] = c.number("a node coordinate", k > 0);
    return x;
  }
  Vec3d coords_binary() {
    Vec3d x;
    for (int k = 0; k < 3; ++k) x[k] = c.raw<double>("node coordinates");
    return x;
  }

  // The binary data follows the header line's newline.
  void to_binary_data() { c.next_line(); }
  // After binary data: the newline before "$End...".
  void expect_end(const char* section) { c.expect(std::string("$End") + section); }

  void nodes_v2() {
    const long long n = c.count("the number of nodes");
    if (binary) to_binary_data();
    for (long long i = 0; i < n; ++i) {
      const std::size_t at = (binary ? c.pos() : (c.skip_space(), c.pos()));
      if (binary) {
        const long long tag = c.raw<std::int32_t>("node tag");
        add_node(tag, coords_binary(), at);
      } else {
        const long long tag = c.integer("a node tag");
        add_node(tag, coords_text(), at);
        if (!c.at_line_end()) c.fail("node " + std::to_string(tag) + ": more than 3 coordinates");
      }
    }
    expect_end("Nodes");
  }

  void elements_v2() {
    const long long m = c.count("the number of elements");
    if (!binary) {
      for (long long i = 0; i < m; ++i) {
        const std::size_t at = (c.skip_space(), c.pos());
        const long long tag = c.integer("an element tag");
        const long long type = c.integer("the element type", true);
        const long long ntags = c.count("the number of element tags", true);
        for (long long t = 0; t < ntags; ++t) c.integer("an element tag value", true);
        std::vector<long long> nodes;
        while (!c.at_line_end()) nodes.push_back(c.integer("a node tag", true));
        if (type == kGmshTet) {
          if (nodes.size() != 4)
            c.fail("element " + std::to_string(tag) + " (a tetrahedron) has " +
                       std::to_string(nodes.size()) + " nodes, not 4", at);
          tets.push_back({{nodes[0], nodes[1], nodes[2], nodes[3]}, tag, at, false});
        }
      }
    } else {
      to_binary_data();
      long long done = 0;
      while (done < m) {
        const std::size_t at = c.pos();
        const long long type = c.raw<std::int32_t>("element block header");
        const long long follow = c.raw<std::int32_t>("element block header");
        const long long ntags = c.raw<std::int32_t>("element block header");
        const int nn = gmsh_nodes_of_type(type);
        if (nn == 0) c.fail("unknown element type " + std::to_string(type), at, true);
        if (follow <= 0 || ntags < 0 || follow > m - done)
          c.fail("bad element block header (" + std::to_string(follow) + " elements, " +
                     std::to_string(ntags) + " tags)", at, true);
        for (long long e = 0; e < follow; ++e) {
          const std::size_t eat = c.pos();
          const long long tag = c.raw<std::int32_t>("element tag");
          for (long long t = 0; t < ntags; ++t) c.raw<std::int32_t>("element tags");
          std::array<long long, 4> nodes{};
          for (int k = 0; k < nn; ++k) {
            const long long v = c.raw<std::int32_t>("element nodes");
            if (k < 4) nodes[k] = v;
          }
          if (type == kGmshTet) tets.push_back({nodes, tag, eat, true});
        }
        done += follow;
      }
    }
    expect_end("Elements");
  }

  void nodes_v4() {
    std::size_t blocks, total;
    long long min_tag, max_tag;  // every node tag lies in [min_tag, max_tag] (the header's)
    if (binary) {
      to_binary_data();
      blocks = c.raw<std::uint64_t>("$Nodes header");
      total = c.raw<std::uint64_t>("$Nodes header");
      min_tag = static_cast<long long>(c.raw<std::uint64_t>("$Nodes header"));
      max_tag = static_cast<long long>(c.raw<std::uint64_t>("$Nodes header"));
    } else {
      blocks = c.count("the number of node blocks");
      total = c.count("the number of nodes", true);
      min_tag = c.integer("the smallest node tag", true);
      max_tag = c.integer("the largest node tag", true);
    }
    std::size_t read = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t at = binary ? c.pos() : (c.skip_space(), c.pos());
      long long dim, param, n;
      if (binary) {
        dim = c.raw<std::int32_t>("node block header");
        c.raw<std::int32_t>("node block header");
        param = c.raw<std::int32_t>("node block header");
        n = static_cast<long long>(c.raw<std::uint64_t>("node block header"));
      } else {
        dim = c.integer("the entity dimension");
        c.integer("the entity tag", true);
        param = c.integer("the parametric flag", true);
        n = c.count("the number of nodes in the block", true);
      }
      // (n is at most the bytes left too: its tags are allocated before they are read)
      if (dim < 0 || dim > 3 || (param != 0 && param != 1) || n < 0 ||
          static_cast<std::size_t>(n) > total - read ||
          static_cast<std::size_t>(n) > c.data().size() - std::min(c.pos(), c.data().size()))
        c.fail("bad node block header", at, binary);
      const int extra = param ? static_cast<int>(dim) : 0;  // parametric coordinates follow
      std::vector<long long> tags(n);
      std::vector<std::size_t> where(n);
      for (long long i = 0; i < n; ++i) {
        where[i] = binary ? c.pos() : (c.skip_space(), c.pos());
        tags[i] = binary ? static_cast<long long>(c.raw<std::uint64_t>("node tags"))
                         : c.integer("a node tag");
        if (tags[i] < min_tag || tags[i] > max_tag)
          c.fail("node tag " + std::to_string(tags[i]) + " is outside the $Nodes header's range [" +
                     std::to_string(min_tag) + ", " + std::to_string(max_tag) + "]",
                 where[i], binary);
      }
      for (long long i = 0; i < n; ++i) {
        const std::size_t cat = binary ? c.pos() : (c.skip_space(), c.pos());
        const Vec3d x = binary ? coords_binary() : coords_text();
        for (int k = 0; k < extra; ++k)
          binary ? c.raw<double>("parametric coordinates") : c.number("a parametric coordinate", true);
        if (!binary && !c.at_line_end())
          c.fail("node " + std::to_string(tags[i]) + ": too many coordinates");
        add_node(tags[i], x, binary ? where[i] : cat);
      }
      read += n;
    }
    if (read != total)
      c.fail("the $Nodes header announces " + std::to_string(total) + " nodes, the blocks hold " +
             std::to_string(read));
    expect_end("Nodes");
  }

  void elements_v4() {
    std::size_t blocks, total;
    if (binary) {
      to_binary_data();
      blocks = c.raw<std::uint64_t>("$Elements header");
      total = c.raw<std::uint64_t>("$Elements header");
      c.raw<std::uint64_t>("$Elements header");
      c.raw<std::uint64_t>("$Elements header");
    } else {
      blocks = c.count("the number of element blocks");
      total = c.count("the number of elements", true);
      c.integer("the smallest element tag", true);
      c.integer("the largest element tag", true);
    }
    std::size_t read = 0;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t at = binary ? c.pos() : (c.skip_space(), c.pos());
      long long type, n;
      if (binary) {
        c.raw<std::int32_t>("element block header");
        c.raw<std::int32_t>("element block header");
        type = c.raw<std::int32_t>("element block header");
        n = static_cast<long long>(c.raw<std::uint64_t>("element block header"));
      } else {
        c.integer("the entity dimension");
        c.integer("the entity tag", true);
        type = c.integer("the element type", true);
        n = c.count("the number of elements in the block", true);
      }
      if (n < 0 || static_cast<std::size_t>(n) > total - read) c.fail("bad element block header", at, binary);
      const int nn = gmsh_nodes_of_type(type);
      if (binary && nn == 0) c.fail("unknown element type " + std::to_string(type), at, true);
      for (long long e = 0; e < n; ++e) {
        const std::size_t eat = binary ? c.pos() : (c.skip_space(), c.pos());
        if (binary) {
          const long long tag = static_cast<long long>(c.raw<std::uint64_t>("element tag"));
          std::array<long long, 4> nodes{};
          for (int k = 0; k < nn; ++k) {
            const long long v = static_cast<long long>(c.raw<std::uint64_t>("element nodes"));
            if (k < 4) nodes[k] = v;
          }
          if (type == kGmshTet) tets.push_back({nodes, tag, eat, true});
        } else {
          const long long tag = c.integer("an element tag");
          std::vector<long long> nodes;
          while (!c.at_line_end()) nodes.push_back(c.integer("a node tag", true));
          if (type == kGmshTet) {
            if (nodes.size() != 4)
              c.fail("element " + std::to_string(tag) + " (a tetrahedron) has " +
                         std::to_string(nodes.size()) + " nodes, not 4", eat);
            tets.push_back({{nodes[0], nodes[1], nodes[2], nodes[3]}, tag, eat, false});
          }
        }
      }
      read += n;
    }
    if (read != total)
      c.fail("the $Elements header announces " + std::to_string(total) +
             " elements, the blocks hold " + std::to_string(read));
    expect_end("Elements");
  }

  // An unknown section: skipped up to its "$End..." line (searched as text; in binary data the
  // string "\n$EndName" does not occur by accident in files Gmsh writes).
  void skip_section(std::string_view name) {
    const std::string end = "$End" + std::string(name.substr(1));
    const std::size_t at = c.pos();
    const std::size_t found = c.data().find("\n" + end, at);
    if (found == std::string::npos) c.fail("section " + std::string(name) + " has no " + end + " (truncated?)", at);
    c.set_pos(found + 1 + end.size());
  }

  Mesh finish() {
    Mesh m;
    m.vertices = std::move(vertices);
    m.vertex_sources = std::move(sources);
    m.tets.reserve(tets.size());
    m.source_ids.reserve(tets.size());
    for (std::size_t i = 0; i < tets.size(); ++i) {
      const PendingTet& t = tets[i];
      std::array<std::size_t, 4> idx{};
      for (int k = 0; k < 4; ++k) {
        const auto it = index_of.find(t.nodes[k]);
        if (it == index_of.end())
          c.fail("element " + std::to_string(t.id) + " (tetrahedron " + std::to_string(i) +
                     ") refers to node " + std::to_string(t.nodes[k]) + ", which is not in the file",
                 t.where, t.binary);
        idx[k] = it->second;
      }
      m.tets.push_back(idx);
      m.source_ids.push_back(t.id);
    }
    return m;
  }
};

Mesh read_msh(Cursor& c) {
  MshState st(c);
  c.expect("$MeshFormat");
  const std::size_t vat = (c.skip_space(), c.pos());
  const std::string version(c.word("the format version"));
  const long long file_type = c.integer("the file type", true);
  const long long data_size = c.integer("the data size", true);
  const bool v2 = version.rfind("2.", 0) == 0;
  if (!v2 && version != "4.1")
    c.fail("MSH version " + version + " is not supported (2.2 and 4.1 are; Gmsh writes either with -format msh22 / msh41)", vat);
  if (file_type != 0 && file_type != 1) c.fail("file type " + std::to_string(file_type) + " is neither 0 (ASCII) nor 1 (binary)", vat);
  if (data_size != 8) c.fail("data size " + std::to_string(data_size) + " is not supported (8 is)", vat);
  st.binary = file_type == 1;
  if (st.binary) {
    c.next_line();
    const std::size_t at = c.pos();
    const std::int32_t one = c.raw<std::int32_t>("the endianness check");
    if (one != 1) c.fail("binary data of the other byte order (the check integer reads " + std::to_string(one) + ")", at, true);
  }
  c.expect("$EndMeshFormat");
  bool nodes = false, elements = false;
  while (!c.at_end()) {
    const std::size_t at = c.pos();
    const std::string_view name = c.word("a section");
    if (name.empty() || name[0] != '$') c.fail("expected a section ($Name), found '" + std::string(name) + "'", at);
    if (name == "$Nodes") {
      if (nodes) c.fail("a second $Nodes section", at);
      v2 ? st.nodes_v2() : st.nodes_v4();
      nodes = true;
    } else if (name == "$Elements") {
      if (elements) c.fail("a second $Elements section", at);
      v2 ? st.elements_v2() : st.elements_v4();
      elements = true;
    } else {
      st.skip_section(name);
    }
  }
  if (!nodes) c.fail("no $Nodes section (truncated?)", c.data().size());
  if (!elements) c.fail("no $Elements section (truncated?)", c.data().size());
  return st.finish();
}

// Legacy VTK: "# vtk DataFile Version x.y", a title line, ASCII|BINARY, DATASET
// UNSTRUCTURED_GRID, POINTS, CELLS (the classic "n size" list, or version 5's OFFSETS and
// CONNECTIVITY arrays), CELL_TYPES; anything after (CELL_DATA, POINT_DATA) is ignored.
// Binary data is big-endian.
Mesh read_vtk(Cursor& c) {
  c.next_line();  // "# vtk DataFile Version x.y"
  c.next_line();  // title
  const std::size_t fat = c.pos();
  const std::string format(c.word("ASCII or BINARY"));
  if (format != "ASCII" && format != "BINARY") c.fail("expected ASCII or BINARY, found '" + format + "'", fat);
  const bool binary = format == "BINARY";
  c.expect("DATASET");
  const std::size_t dat = (c.skip_space(), c.pos());
  const std::string dataset(c.word("the dataset type"));
  if (dataset != "UNSTRUCTURED_GRID")
    c.fail("dataset " + dataset + " is not an unstructured grid (DATASET UNSTRUCTURED_GRID)", dat);

  auto int_of = [&](const std::string& type, const char* what) -> long long {
    if (!binary) return c.integer(what);
    if (type == "vtktypeint64" || type == "long") return c.raw<std::int64_t>(what, true);
    return c.raw<std::int32_t>(what, true);
  };
  Mesh m;
  std::vector<std::vector<long long>> cells;
  std::vector<std::size_t> cell_where;
  std::vector<long long> types;
  bool have_points = false, have_cells = false, have_types = false;
  while (!(have_points && have_cells && have_types)) {
    if (c.at_end()) break;
    const std::size_t at = c.pos();
    const std::string key(c.word("a keyword"));
    if (key == "POINTS") {
      const long long n = c.count("the number of points", true);
      const std::string type(c.word_on_line("the point type"));
      static const char* const kTypes[] = {"unsigned_char", "char",  "unsigned_short", "short", "unsigned_int",
                                           "int",           "unsigned_long", "long", "float", "double"};
      if (std::find(std::begin(kTypes), std::end(kTypes), type) == std::end(kTypes))
        c.fail("'" + type + "' is not a VTK data type", at);
      if (binary && type != "float" && type != "double")
        c.fail("binary point type '" + type + "' is not supported (float, double are)", at);
      if (binary) c.next_line();
      m.vertices.resize(n);
      for (long long i = 0; i < n; ++i) {
        const std::size_t pat = binary ? c.pos() : (c.skip_space(), c.pos());
        for (int k = 0; k < 3; ++k)
          m.vertices[i][k] = !binary ? c.number("a point coordinate")
                             : type == "float" ? c.raw<float>("point coordinates", true)
                                               : c.raw<double>("point coordinates", true);
        const Vec3d& x = m.vertices[i];
        if (!(std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2])))  // the file's own numbering
          m.vertex_sources.emplace(i, "point " + std::to_string(i) + " at " + c.location(pat, binary));
      }
      have_points = true;
    } else if (key == "CELLS") {
      const long long n = c.count("the number of cells", true);
      const long long size = c.count("the size of the cell list", true);
      const std::size_t after = c.pos();
      c.next_line();
      const std::size_t peek = c.pos();
      const bool v5 = !c.at_end() && c.word("") == "OFFSETS";
      if (v5) {
        const std::string otype(c.word_on_line("the offset type"));
        if (binary) c.next_line();
        std::vector<long long> offsets(n);
        for (auto& o : offsets) o = int_of(otype, "cell offsets");
        c.expect("CONNECTIVITY");
        const std::string ctype(c.word_on_line("the connectivity type"));
        if (binary) c.next_line();
        std::vector<long long> conn(size);
        std::vector<std::size_t> conn_where(size);
        for (long long i = 0; i < size; ++i) {
          conn_where[i] = binary ? c.pos() : (c.skip_space(), c.pos());
          conn[i] = int_of(ctype, "cell connectivity");
        }
        for (long long i = 0; i + 1 < n; ++i) {
          if (offsets[i] < 0 || offsets[i] > offsets[i + 1] || offsets[i + 1] > size)
            c.fail("cell " + std::to_string(i) + ": bad offsets", at);
          cells.emplace_back(conn.begin() + offsets[i], conn.begin() + offsets[i + 1]);
          cell_where.push_back(offsets[i] < size ? conn_where[offsets[i]] : at);
        }
      } else {
        c.set_pos(binary ? peek : after);
        long long listed = 0;  // the legacy list's length: a size and k indices per cell
        for (long long i = 0; i < n; ++i) {
          const std::size_t cat = binary ? c.pos() : (c.skip_space(), c.pos());
          const long long k = binary ? c.raw<std::int32_t>("cell sizes", true) : c.count("a cell size");
          if (k < 0 || k > 1000) c.fail("cell " + std::to_string(i) + " has " + std::to_string(k) + " points", cat, binary);
          std::vector<long long> ids(k);
          for (auto& v : ids) v = binary ? c.raw<std::int32_t>("cell points", true) : c.integer("a cell point index", true);
          cells.push_back(std::move(ids));
          cell_where.push_back(cat);
          listed += 1 + k;
        }
        if (listed != size)  // (e.g. "CELLS 2 3" over two tetrahedra)
          c.fail("the cell list has " + std::to_string(listed) + " numbers, not the " + std::to_string(size) +
                     " its header says",
                 at);
      }
      have_cells = true;
    } else if (key == "CELL_TYPES") {
      const long long n = c.count("the number of cell types", true);
      if (binary) c.next_line();
      types.resize(n);
      for (auto& t : types) t = binary ? c.raw<std::int32_t>("cell types", true) : c.integer("a cell type");
      have_types = true;
    } else if (key == "METADATA") {
      // Version 5 metadata block: ends at an empty line.
      const std::size_t e = c.data().find("\n\n", c.pos());
      c.set_pos(e == std::string::npos ? c.data().size() : e + 2);
    } else {
      c.fail("'" + key + "' where POINTS, CELLS or CELL_TYPES was expected (other data before the cells is not supported)", at);
    }
  }
  if (!have_points) c.fail("no POINTS (truncated?)", c.data().size());
  if (!have_cells) c.fail("no CELLS (truncated?)", c.data().size());
  if (!have_types) c.fail("no CELL_TYPES (truncated?)", c.data().size());
  if (types.size() != cells.size())
    c.fail(std::to_string(cells.size()) + " cells but " + std::to_string(types.size()) + " cell types", c.data().size());
  constexpr long long kVtkTetra = 10;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (types[i] != kVtkTetra) continue;
    if (cells[i].size() != 4)
      c.fail("cell " + std::to_string(i) + " (type 10, a tetrahedron) has " + std::to_string(cells[i].size()) + " points, not 4",
             cell_where[i], binary);
    std::array<std::size_t, 4> t{};
    for (int k = 0; k < 4; ++k) {
      if (cells[i][k] < 0 || cells[i][k] >= static_cast<long long>(m.vertices.size()))
        c.fail("cell " + std::to_string(i) + " (tetrahedron " + std::to_string(m.tets.size()) +
                   ") refers to point " + std::to_string(cells[i][k]) + ", which is not in the file (" +
                   std::to_string(m.vertices.size()) + " points)",
               cell_where[i], binary);
      t[k] = static_cast<std::size_t>(cells[i][k]);
    }
    m.tets.push_back(t);
    m.source_ids.push_back(static_cast<long long>(i));
  }
  return m;
}

}  // namespace

Mesh read_mesh(const std::string& path) {
  Cursor c(path, read_file(path));
  const std::string& s = c.data();
  if (s.empty()) throw ReadError(path + ": the file is empty");
  std::size_t b = 0;
  while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  Mesh m;
  if (s.compare(b, 11, "$MeshFormat") == 0)
    m = read_msh(c);
  else if (s.compare(b, 14, "# vtk DataFile") == 0)
    m = read_vtk(c);
  else
    throw ReadError(path + ": neither a Gmsh mesh ($MeshFormat) nor a legacy VTK file (# vtk DataFile)");
  // Other elements are ignored; a file of nothing else has nothing to compute, and saying so
  // beats an empty result that reads as "no contact".
  if (m.tets.empty())
    throw ReadError(path + ": no first-order tetrahedra (4-node elements: Gmsh type 4, VTK cell type 10); "
                    "surface, second-order and hexahedral elements are ignored");
  return m;
}

}  // namespace pdd::mesh
