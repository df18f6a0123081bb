// direction_label.h — labels of candidate separating directions (definitions §3), plain data.
//
//   FV:i      face of A opposite s_i           (i = 0..3)
//   VF:j      face of B opposite r_j           (j = 0..3)
//   EE:a:b    edge a of A against edge b of B  (a, b = 0..5, edges in kEdges order)
//   EE:a:b:+ / EE:a:b:-   the two orientations of an undecidable edge pair
//
// Canonical order: all FV, then all VF, then EE by (a, b), and ':+' before ':-'.
#pragma once

#include <array>
#include <optional>
#include <ostream>
#include <string>
#include <tuple>

#include "pdd/tet_tables.h"  // kEdges: the edge numbering of EE labels

namespace pdd {

enum class ContactKind { FV = 0, VF = 1, EE = 2 };

// Decided: the orientation rule chose one sign. Plus/Minus: undecidable pair, n or -n.
enum class EdgeOrientation { Decided = 0, Plus = 1, Minus = 2 };

struct DirectionLabel {
  ContactKind kind = ContactKind::FV;
  int a = 0;  // FV: i; VF: j; EE: edge of A
  int b = 0;  // EE: edge of B; 0 otherwise
  EdgeOrientation orientation = EdgeOrientation::Decided;

  std::string str() const {
    switch (kind) {
      case ContactKind::FV: return "FV:" + std::to_string(a);
      case ContactKind::VF: return "VF:" + std::to_string(a);
      case ContactKind::EE: break;
    }
    std::string s = "EE:" + std::to_string(a) + ":" + std::to_string(b);
    if (orientation == EdgeOrientation::Plus) s += ":+";
    if (orientation == EdgeOrientation::Minus) s += ":-";
    return s;
  }

  // Position in canonical order; a strict weak order consistent with definitions §3.
  auto key() const { return std::make_tuple(int(kind), a, b, int(orientation)); }
  bool operator==(const DirectionLabel& o) const { return key() == o.key(); }
  bool operator!=(const DirectionLabel& o) const { return !(*this == o); }
  bool operator<(const DirectionLabel& o) const { return key() < o.key(); }

  static DirectionLabel fv(int i) { return {ContactKind::FV, i, 0, EdgeOrientation::Decided}; }
  static DirectionLabel vf(int j) { return {ContactKind::VF, j, 0, EdgeOrientation::Decided}; }
  static DirectionLabel ee(int a, int b, EdgeOrientation o = EdgeOrientation::Decided) {
    return {ContactKind::EE, a, b, o};
  }

  // Inverse of str(); nullopt for anything that is not a well-formed label.
  static std::optional<DirectionLabel> parse(const std::string& s) {
    auto digit = [&](size_t pos, int hi) -> int {
      if (pos >= s.size() || s[pos] < '0' || s[pos] > char('0' + hi)) return -1;
      return s[pos] - '0';
    };
    if (s.size() == 4 && (s.compare(0, 3, "FV:") == 0 || s.compare(0, 3, "VF:") == 0)) {
      int i = digit(3, 3);
      if (i < 0) return std::nullopt;
      return s[0] == 'F' ? fv(i) : vf(i);
    }
    if ((s.size() == 6 || s.size() == 8) && s.compare(0, 3, "EE:") == 0 && s[4] == ':') {
      int a = digit(3, 5), b = digit(5, 5);
      if (a < 0 || b < 0) return std::nullopt;
      if (s.size() == 6) return ee(a, b);
      if (s[6] != ':' || (s[7] != '+' && s[7] != '-')) return std::nullopt;
      return ee(a, b, s[7] == '+' ? EdgeOrientation::Plus : EdgeOrientation::Minus);
    }
    return std::nullopt;
  }
};

inline std::ostream& operator<<(std::ostream& os, const DirectionLabel& l) { return os << l.str(); }

}  // namespace pdd
