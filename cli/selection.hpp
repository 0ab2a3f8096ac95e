#pragma once
/// \file selection.hpp
/// The options that choose a pattern of M, an obstacle, an asymptotic regime
/// and evolution cases, shared by the commands that work on derivations
/// (`derive`, `verify`, `explore`); resolved by superball/present/selection.hpp,
/// whose types and parsers hold every rule on them.

#include <CLI/CLI.hpp>

#include <string>

#include "superball/present/selection.hpp"

namespace superball::cli {

using present::Selection;

/// The command line's selection options: present::SelectionOptions, with
/// --alphas and --obstacle kept as the text given, which typed() reads with
/// the library's parse_alphas() and parse_obstacle().
struct SelectionOptions : present::SelectionOptions {
  std::string alphas_text, obstacle_text = "infinite";
  bool require_case = true;  ///< resolve() refuses a choice of no case (present::require_case())
  /// The library's options, the texts read (std::invalid_argument from the library's parsers).
  present::SelectionOptions typed() const;
};

/// present::resolve() of \p o.typed(), after present::require_case() when o.require_case.
Selection resolve(const SelectionOptions& o);

/// Register --bodies, --case/--closed/--all (one of them required when
/// \p require_case), --alphas, --coupling, --pairs, --scene, --obstacle,
/// --scaling and --order on \p cmd, writing into \p o.
void add_selection_options(CLI::App* cmd, SelectionOptions& o, bool require_case = true);

}  // namespace superball::cli
