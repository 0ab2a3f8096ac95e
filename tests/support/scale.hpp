#pragma once
/// \file scale.hpp
/// How many repetitions a test whose work is repetition runs.  The
/// sanitizer stage of scripts/test.sh sets SUPERBALL_TEST_SCALE=small: there
/// every process runs ten to twenty times slower, and the thousandth random
/// scene or the fourth worker count goes through the code paths the first
/// ones went through.  Such a test then runs fewer repetitions (fewer random
/// cases, fewer worker counts, fewer spellings of one option), with its
/// assertions unchanged.  Unset or `full`: every repetition.

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace superball::test {

/// True when SUPERBALL_TEST_SCALE is `small`, false when it is unset, empty or
/// `full`; any other value is a mistake in the caller's environment.
inline bool small_scale() {
  const char* value = std::getenv("SUPERBALL_TEST_SCALE");
  const std::string s = value ? value : "";
  if (s.empty() || s == "full") return false;
  if (s == "small") return true;
  throw std::invalid_argument("small_scale(): SUPERBALL_TEST_SCALE must be full or small, got '" + s + "'");
}

}  // namespace superball::test
