// The Fig. 7 switch points (paper §4.4 read with α₂ = −100, sweeping K₃₄)
// are rational, by the symbolic backend: in case 3.3 (no contact closed)
// the gaps U₂⁺ − U₃⁺ and U₃⁺ − U₄⁺, with every parameter but K₃₄ set to the
// scene's exact values, have numerators of degree one in K₃₄.  Their roots
// are then checked with the exact numeric solver: there the contact's gap
// and reaction are both exactly 0 (tests/numeric/switch_point_test.cpp
// finds the same points from forced numeric solves).
#include <gtest/gtest.h>

#include <cln/rational_io.h>
#include <ginac/ginac.h>

#include <iostream>
#include <sstream>
#include <string>

#include "superball/cases/parameter.hpp"
#include "superball/cases/scene_file.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/sweep.hpp"
#include "superball/symbolic/derivation.hpp"

namespace superball {
namespace {

const std::string kScene = std::string(SUPERBALL_CASES_DIR) + "/scenes/paper-4.4-alpha2.toml";

/// A CLN rational as a GiNaC number (through its exact text).
GiNaC::ex ginac_of(const cln::cl_RA& x) {
  std::ostringstream os;
  cln::fprint(os, x);
  return GiNaC::numeric(os.str().c_str());
}

/// A GiNaC rational number as a CLN rational.
cln::cl_RA cln_of(const GiNaC::ex& x) {
  std::ostringstream os;
  os << x;
  return cln::cl_RA(os.str().c_str());
}

/// The symbols of the scene's pattern set to its exact values, except \p keep
/// (the fall speed is 1: the collision is homogeneous in it).
GiNaC::exmap values_except(const symbolic::Symbols& symbols, const numeric::ExactScene& scene, const GiNaC::ex& keep) {
  GiNaC::exmap out;
  for (const symbolic::SymbolInfo& s : symbols.all()) {
    if (s.symbol.is_equal(keep)) continue;
    switch (s.kind) {
      case symbolic::SymbolKind::Mass: out[s.symbol] = ginac_of(scene.mass[static_cast<std::size_t>(s.body - 1)]); break;
      case symbolic::SymbolKind::FallSpeed: out[s.symbol] = 1; break;
      case symbolic::SymbolKind::Diagonal:
      case symbolic::SymbolKind::Coupling:
        for (const auto& e : scene.entries) {
          const Pair p{e.i + 1, e.j + 1}, q{e.k + 1, e.l + 1};
          if ((p == s.first && q == s.second) || (p == s.second && q == s.first)) out[s.symbol] = ginac_of(e.value);
        }
        break;
    }
    EXPECT_TRUE(out.count(s.symbol)) << "no value for " << s.ascii;
  }
  return out;
}

TEST(SwitchPointSymbolic, Fig7ThresholdsAreRationalAndExactlyOnTheEdge) {
  const Scene scene = load_scene(kScene);
  const numeric::ExactScene exact = numeric::ExactScene::from(scene);
  const symbolic::Pattern pattern = symbolic::Pattern::from_scene(scene);
  const symbolic::Obstacle obstacle = exact.fixed_bottom ? symbolic::Obstacle::Infinite : symbolic::Obstacle::Finite;
  const symbolic::Symbols symbols(pattern, obstacle);
  const symbolic::Deriver deriver(pattern, obstacle, symbolic::Scaling::parse("none", symbols));
  const symbolic::Derivation d = deriver.derive(ContactSet(4));  // case 3.3
  const GiNaC::ex& k34 = deriver.symbols().diagonal(Pair{3, 4});
  const GiNaC::exmap values = values_except(deriver.symbols(), exact, k34);
  const Parameter parameter = Parameter::parse("K.3-4", scene);
  for (int c : {2, 1}) {  // contact 3-4 (switch with case 2.2), then 2-3 (with case 3.2)
    SCOPED_TRACE("contact " + std::to_string(c + 1) + "-" + std::to_string(c + 2));
    const GiNaC::ex gap = GiNaC::normal((d.velocities[static_cast<std::size_t>(c)].value() -
                                         d.velocities[static_cast<std::size_t>(c + 1)].value()).subs(values));
    const GiNaC::ex nd = GiNaC::numer_denom(gap);
    const GiNaC::ex numerator = GiNaC::expand(nd.op(0));
    ASSERT_EQ(numerator.degree(k34), 1) << "numerator " << numerator;
    const GiNaC::ex root = GiNaC::normal(-numerator.coeff(k34, 0) / numerator.coeff(k34, 1));
    ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(root) && GiNaC::ex_to<GiNaC::numeric>(root).is_rational()) << root;
    EXPECT_FALSE(GiNaC::normal(nd.op(1).subs(k34 == root)).is_zero()) << "the denominator vanishes at the root";
    std::cout << "[ info ] contact " << c + 1 << "-" << c + 2 << " on the edge at K34 = " << root << " (numerator of the gap of degree 1 in K34)\n";
    // The exact solution at the root: the contact is on the edge.
    const auto at = numeric::solve_exact_at(scene, parameter, cln_of(root));
    ASSERT_EQ(at.solution.status, numeric::Status::Success);
    EXPECT_EQ(at.solution.gaps[static_cast<std::size_t>(c)], 0) << "K34 = " << root;
    EXPECT_EQ(at.solution.reactions[static_cast<std::size_t>(c)], 0) << "K34 = " << root;
    EXPECT_TRUE(at.solution.closed.closed(c)) << "the label at a switch point is closed";
  }
}

}  // namespace
}  // namespace superball
