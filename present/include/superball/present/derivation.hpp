#pragma once
/// \file derivation.hpp
/// A derivation for programs: the JSON of `superball derive --format json`,
/// shared by the command and the Python module; not installed.

#include <nlohmann/json.hpp>

#include <vector>

#include "superball/symbolic/derivation.hpp"

namespace superball::present {

/// Whether the text report writes \p p (the numerator of a velocity or a
/// reaction of \p d, or its determinant) through the case's elimination,
/// and the compact JSON likewise: the case has one and \p p has more than
/// symbolic::max_inline_exact_terms terms.
bool through_elimination(const symbolic::Derivation& d, const GiNaC::ex& p);

/// One condition: kind, about, the exact and asymptotic forms in ASCII
/// (GiNaC's syntax), text and LaTeX, the readable and eliminated forms when
/// there are, the order in ε, the verdicts and the proof.  Compact (not
/// \p expanded): a form written through the case's elimination (an
/// `eliminated` form) leaves out its expanded forms (exact, text, latex;
/// asymptotic, asymptotic_text, asymptotic_latex; finite).
nlohmann::ordered_json condition_json(const symbolic::Condition& c, const symbolic::Symbols& s, bool expanded);

/// The case \p d of \p deriver: symbols, velocities, reactions, the
/// determinant, named parts, the elimination when set, and the conditions.
/// \p psd holds the JSON of the conditions on M (Deriver::psd(), the same in
/// every case), made on the first call and reused: with many cases they
/// were most of the conditions written.  Compact (not \p expanded, the
/// command's default): the conditions as condition_json() says, and a
/// velocity, reaction or determinant that the text report writes through the
/// elimination is that form over the names of `elimination.definitions`
/// ("V1", "p1*p2*p3"); \p expanded writes every expanded form (1.7 GB at 8
/// bodies against 12 MB).  \p with_psd false leaves out the conditions on
/// M: a compact list of several cases has them in its first case only, as
/// the text report writes them once (at 8 bodies they were 104 MB of the
/// 144 MB when repeated in every case).
nlohmann::ordered_json derivation_json(const symbolic::Derivation& d, const symbolic::Deriver& deriver,
                                       std::vector<nlohmann::ordered_json>& psd, bool expanded, bool with_psd = true);

}  // namespace superball::present
