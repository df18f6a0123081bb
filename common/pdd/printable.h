// printable.h — text from an input file (a pair's name, a mesh's section name) as a message
// shows it: control characters (NUL, a newline, a terminal escape) as \xNN, so that the text
// can neither cut the message short nor forge or garble the lines around it (a NUL would cut
// a mesh message at "section $No", a name would print a newline and an escape).
#pragma once

#include <string>

namespace pdd {

inline std::string printable(const std::string& s) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  out.reserve(s.size());
  for (const unsigned char ch : s) {
    if (ch < 0x20 || ch == 0x7f) {
      out += "\\x";
      out += kHex[ch >> 4];
      out += kHex[ch & 15];
    } else {
      out += static_cast<char>(ch);
    }
  }
  return out;
}

}  // namespace pdd
