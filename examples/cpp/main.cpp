// Solve a scene numerically (double and exact rationals), print the report
// `superball solve` prints, and derive the paper's case 1 with the coupling
// α₂ symbolically, with superball's installed libraries.
// Usage: superball_example [SCENE]
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "superball/cases/scene_file.hpp"
#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/present/solution.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/format.hpp"

int main(int argc, char** argv) {
  using namespace superball;
  try {
    const std::string path = argc > 1 ? argv[1] : SUPERBALL_EXAMPLE_SCENE;
    const Scene scene = load_scene(path);
    const numeric::ExactScene exact = numeric::ExactScene::from(scene);

    // In double: U⁺ in the problem's unit, times the unit (the fall speed a).
    const auto problem = numeric::Problem<double>::from(exact);
    const auto solution = numeric::solve(problem);
    std::cout << scene.title << ": case " << Vocabulary::paper().case_name(solution.closed) << ", "
              << numeric::to_string(solution.status) << "\n";
    for (int i = 0; i < scene.size(); ++i) {
      std::printf("  U%d+ = %.6g m/s\n", i + 1, solution.velocities_after[static_cast<std::size_t>(i)] * problem.unit);
    }

    // In exact rationals: the top ball's velocity as a fraction.
    const auto rational = numeric::Problem<cln::cl_RA>::from(exact);
    const auto exact_solution = numeric::solve(rational);
    if (rational.unit_exact) {
      std::cout << "  U1+ exactly " << numeric::to_string(cln::cl_RA(exact_solution.velocities_after[0] * rational.unit)) << "\n";
    }

    // The report `superball solve SCENE --precision double` prints (superball::present).
    std::cout << "\n" << present::to_text(present::solve_scene(scene, numeric::Precision{})) << "\n";

    // Symbolically: case 1 of the paper with α₂, the superball condition.
    const symbolic::Deriver deriver(symbolic::Pattern::paper({2}), symbolic::Obstacle::Infinite);
    const symbolic::Derivation d = deriver.derive(Vocabulary::paper().named_case("1").closed);
    std::cout << "case " << d.case_name << ", U1+ = "
              << symbolic::format_fraction(d.velocities[0], deriver.symbols(), symbolic::Style::Text) << "\n";
    for (const symbolic::Condition& c : d.conditions) {
      if (c.kind != symbolic::ConditionKind::Superball) continue;
      std::cout << "  superball when " << symbolic::format_form(c.exact, c.relation, deriver.symbols(), symbolic::Style::Text)
                << "\n  asymptotically " << symbolic::format_form(c.asymptotic, c.relation, deriver.symbols(), symbolic::Style::Text)
                << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "superball_example: " << e.what() << "\n";
    return 2;
  }
}
