#pragma once
/// \file selection.hpp
/// The options that choose a pattern of M, an obstacle, an asymptotic regime
/// and evolution cases, shared by the commands that work on derivations
/// (`derive`, `verify`, `explore`); resolved by superball/present/selection.hpp.

#include <CLI/CLI.hpp>

#include "superball/present/selection.hpp"

namespace superball::cli {

using present::parse_alphas;
using present::resolve;
using present::Selection;
using present::SelectionOptions;

/// Register --bodies, --case/--closed/--all (one of them required when
/// \p require_case), --alphas, --coupling, --pairs, --scene, --obstacle,
/// --scaling and --order on \p cmd, writing into \p o.
void add_selection_options(CLI::App* cmd, SelectionOptions& o, bool require_case = true);

}  // namespace superball::cli
