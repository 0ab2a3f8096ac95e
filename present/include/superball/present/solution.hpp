#pragma once
/// \file solution.hpp
/// A solution as people and programs read it: values scaled from the
/// solver's velocity unit to SI, as JSON and as text.  Shared by the
/// `superball` command and the Python module (the two fronts of the
/// libraries).

#include <nlohmann/json.hpp>

#include <string>

#include "superball/numeric/collision.hpp"
#include "superball/numeric/flight.hpp"
#include "superball/numeric/precision.hpp"
#include "superball/present/export.hpp"
SUPERBALL_PRESENT_API_BEGIN

namespace superball::present {

/// One solved scene, in any precision, flattened for output.
struct Presented {
  ///@{
  /// The scene's file (or "<scene>") and title, the arithmetic's name
  /// ("double", "exact", …), the solve's status ("success", …) and the
  /// paper's name of the evolution case found ("3.3").
  std::string origin, title, precision, status, case_name;
  ///@}
  ///@{
  /// The number of bodies and the active-set pivots the solve took.
  int n = 0, pivots = 0;
  ///@}
  ///@{
  /// Whether the bottom body is a fixed obstacle (mass ∞), and whether the
  /// result is the superball (U₁⁺ > |U₁⁻|).
  bool fixed_bottom = false, superball = false;
  ///@}
  ///@{
  /// In SI units as doubles: the masses (∞ for a fixed obstacle), the
  /// velocities before (U⁻) and after (U⁺), the reactions on the contacts
  /// (c, c+1).
  std::vector<double> masses, before, after, reactions;
  ///@}
  ///@{
  /// U⁺ and the reactions as text.
  std::vector<std::string> after_text, reaction_text;  ///< full precision (exact: fractions)
  ///@}
  /// The masses, U⁻, U⁺ and the reactions (six significant digits) and the
  /// energies (eight) from the solve's own arithmetic, for the text: their
  /// doubles are ±inf or 0 where S holds a value beyond double's range
  /// (−1e400 in long double).
  struct Short {
    ///@{
    /// The masses, U⁻, U⁺ and the reactions, six significant digits.
    std::vector<std::string> masses, before, after, reactions;
    ///@}
    ///@{
    /// The kinetic energies before and after and the energy dissipated, eight significant digits.
    std::string ke_before, ke_after, dissipation;
    ///@}
  } shown;  ///< the values the text shows
  /// The contacts that stay closed ("2-3").
  std::vector<std::string> closed;
  ///@{
  /// The kinetic energies before and after, the energy dissipated, and the
  /// momenta before and after, in SI units.
  double ke_before = 0, ke_after = 0, dissipation = 0, momentum_before = 0, momentum_after = 0;
  ///@}
  ///@{
  /// The solve's largest relative residuals of the equations of motion and
  /// of the complementarity conditions (numeric::Solution).
  double residual_motion = 0, residual_complementarity = 0;
  ///@}
  /// Solved in exact rationals.
  bool exact = false;
  std::vector<numeric::BodyFlight> flight;  ///< only when the scene asks for it ([flight])
  std::string requested;                    ///< "auto" when the precision was chosen by certification
  double error_bound = -1;                  ///< certified relative velocity error (auto only)
  std::vector<std::string> escalation;      ///< what auto tried
  /// Why an explicitly chosen arithmetic's answer cannot be trusted
  /// (numeric::trust_warnings(): its case is not certified, or its certified
  /// bound is vacuous); empty when it can, and always for exact and auto.
  std::vector<std::string> warnings;
  ///@{
  /// The gravity and the flight's duration (s) of a scene that asks for its flight.
  double g = 9.81, flight_duration = 0;
  ///@}
};

/// Solve \p scene in \p precision and flatten the result.
Presented solve_scene(const Scene& scene, const numeric::Precision& precision);
/// Solve \p scene with `--precision auto`: the first of double, long double
/// and exact whose result is certified to \p rtol (numeric/certify.hpp).
Presented solve_scene_auto(const Scene& scene, double rtol);

/// Every field of \p p, for programs (`superball solve --json`).
nlohmann::json to_json(const Presented& p);
/// \p p for people (`superball solve`).
std::string to_text(const Presented& p);

}  // namespace superball::present

SUPERBALL_PRESENT_API_END
