#pragma once
/// \file vocabulary.hpp
/// The paper's names, read from cases/paper/vocabulary.toml (compiled into the
/// library): the evolution cases of §4 for n = 4 and the couplings α₁…α₇ of
/// the matrix M of §3.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "superball/cases/model.hpp"
#include "superball/cases/export.hpp"
SUPERBALL_CASES_API_BEGIN

namespace superball {

/// A named evolution case of the paper (n = 4).
struct NamedCase {
  std::string name;         ///< "1", "2.1", …
  ContactSet closed;        ///< the contacts that stay closed
  std::string description;  ///< the paper's words
};

/// A named coupling of M (paper §3, n = 4): α_k couples two pairs.
struct NamedCoupling {
  int index = 0;  ///< k in α_k
  /// The first pair coupled (first < second).
  Pair first;
  /// The second pair coupled.
  Pair second;
};

/// The paper's vocabulary, loaded once.
class Vocabulary {
 public:
  /// The vocabulary compiled into the library.
  static const Vocabulary& paper();
  /// Parse a vocabulary file's text; throws std::runtime_error("Vocabulary: ...").
  static Vocabulary parse(const std::string& text, const std::string& origin);

  /// The paper's named evolution cases, in the paper's order.
  const std::vector<NamedCase>& cases() const { return cases_; }
  /// The couplings α₁…α₇, by index.
  const std::vector<NamedCoupling>& alphas() const { return alphas_; }
  /// The number of bodies the vocabulary is for (4).
  int bodies() const { return bodies_; }

  /// The paper's name of \p set (n = 4), else the set itself, "{2-3,3-4}".
  std::string case_name(const ContactSet& set) const;
  /// The case called \p name; throws std::invalid_argument("Vocabulary::named_case(): ...").
  const NamedCase& named_case(const std::string& name) const;
  /// α_k; throws std::invalid_argument("Vocabulary::alpha(): ...") for k outside 1..7.
  const NamedCoupling& alpha(int k) const;
  /// The k of the α coupling (p, q), if it is one.
  std::optional<int> alpha_index(const Pair& p, const Pair& q) const;

 private:
  int bodies_ = 4;
  std::vector<NamedCase> cases_;
  std::vector<NamedCoupling> alphas_;
};

}  // namespace superball

SUPERBALL_CASES_API_END
