#pragma once
/// \file paper_data.hpp (internal)
/// The files of cases/paper/, compiled into the library.

#include <string>

namespace superball::detail {

/// The text of cases/paper/\p name (e.g. "vocabulary.toml"); throws
/// std::invalid_argument("paper_file(): ...") for a file that was not compiled in.
const std::string& paper_file(const std::string& name);

}  // namespace superball::detail
