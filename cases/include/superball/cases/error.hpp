#pragma once
/// \file error.hpp
/// The project's input error and message helpers.

#include <stdexcept>
#include <string>
#include <string_view>
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// An input error: one line "FILE:LINE:COL: FIELD: what is wrong" (or
/// "FILE: FIELD: …" where no place in the file applies).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// \p text with every control character written as an escape, so that a
/// message echoing user text stays one line and sends no raw control bytes to
/// a terminal: `\0`, `\t`, `\n`, `\r`, `\e` (ESC), other C0 controls and DEL
/// as `\xHH`, C1 controls (U+0080..U+009F, UTF-8 `C2 80`..`C2 9F`) as `\uHHHH`.
/// Every other byte (printable ASCII, other UTF-8) is kept as it is.
inline std::string printable(std::string_view text) {
  static constexpr char hex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (std::size_t k = 0; k < text.size(); ++k) {
    const auto c = static_cast<unsigned char>(text[k]);
    if (c == 0xc2 && k + 1 < text.size() && static_cast<unsigned char>(text[k + 1]) >= 0x80 &&
        static_cast<unsigned char>(text[k + 1]) <= 0x9f) {
      const auto d = static_cast<unsigned char>(text[++k]);
      out += "\\u00";
      out += hex[d >> 4];
      out += hex[d & 15];
    } else if (c >= 0x20 && c != 0x7f) {
      out += text[k];
    } else if (c == 0) {
      out += "\\0";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == 0x1b) {
      out += "\\e";
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

/// The reason of an exception message written as "function(): reason"
/// (GiNaC style), without the function prefix; the whole message otherwise.
inline std::string without_function_prefix(const std::string& message) {
  const auto at = message.find("(): ");
  return at == std::string::npos ? message : message.substr(at + 4);
}

}  // namespace superball

SUPERBALL_CASES_API_END
