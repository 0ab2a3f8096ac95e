#pragma once
/// \file error.hpp
/// The project's input error and message helpers.

#include <stdexcept>
#include <string>

namespace superball {

/// An input error: one line "FILE:LINE:COL: FIELD: what is wrong" (or
/// "FILE: FIELD: …" where no place in the file applies).
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The reason of an exception message written as "function(): reason"
/// (GiNaC style), without the function prefix; the whole message otherwise.
inline std::string without_function_prefix(const std::string& message) {
  const auto at = message.find("(): ");
  return at == std::string::npos ? message : message.substr(at + 4);
}

}  // namespace superball
