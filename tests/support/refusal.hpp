#pragma once
// What a library call refuses, as a test compares it: the message of its
// std::invalid_argument without the "function(): " prefix (the text both
// fronts show after "superball: ").
#include <stdexcept>
#include <string>

#include "superball/cases/error.hpp"

namespace superball::test {

/// The message of the std::invalid_argument \p f throws, without its "function(): " prefix; "" when it throws none.
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return without_function_prefix(e.what());
  }
  return "";
}

}  // namespace superball::test
