// Hand-rolled JSON text for the writers. Numbers are printed from whole millimetres with integer
// arithmetic only (no printf of doubles, whose shortest-digits output varies between C
// libraries), which is what makes the output byte-identical everywhere.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

namespace urbanpvs::cities::detail {

/// Metres (a whole number of millimetres) to the integer number of millimetres.
inline std::int64_t toMillimetres(double metres) {
  return std::llround(metres * 1000.0);
}

inline void appendInt(std::string& out, std::int64_t v) {
  char buf[24];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

/// Millimetres as metres with exactly three decimals: 12345 -> "12.345", -5 -> "-0.005".
inline void appendMetres(std::string& out, std::int64_t mm) {
  if (mm < 0) {
    out += '-';
    mm = -mm;
  }
  appendInt(out, mm / 1000);
  const auto frac = static_cast<int>(mm % 1000);
  out += '.';
  out += static_cast<char>('0' + frac / 100);
  out += static_cast<char>('0' + frac / 10 % 10);
  out += static_cast<char>('0' + frac % 10);
}

/// A JSON string literal. Ids and attribute values are ASCII; control characters and quotes
/// are escaped anyway.
inline void appendString(std::string& out, std::string_view s) {
  out += '"';
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\u00";
      out += kHex[(ch >> 4) & 0xF];
      out += kHex[ch & 0xF];
    } else {
      out += ch;
    }
  }
  out += '"';
}

}  // namespace urbanpvs::cities::detail
