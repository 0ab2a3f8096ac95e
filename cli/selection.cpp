#include "selection.hpp"

#include "commands.hpp"

namespace superball::cli {

present::SelectionOptions SelectionOptions::typed() const {
  present::SelectionOptions o = *this;
  if (!alphas_text.empty()) o.alphas = present::parse_alphas(alphas_text);
  o.obstacle = present::parse_obstacle(obstacle_text);
  return o;
}

Selection resolve(const SelectionOptions& o) {
  const present::SelectionOptions typed = o.typed();
  if (o.require_case) present::require_case(typed);
  return present::resolve(typed);
}

void add_selection_options(CLI::App* cmd, SelectionOptions& o, bool require_case) {
  cmd->add_option("--bodies,-n", o.bodies,
                  "Number of bodies n, the bottom one being the obstacle: 2 to 21 (20 with --obstacle finite); default " +
                      std::to_string(present::default_bodies));
  auto* g = cmd->add_option_group("case", "Which evolution case (one of)");
  g->add_option("--case", o.case_name, "The paper's case name (n = 4): 0, 1, 2.1, 2.2, 3.1, 3.2, 3.3, 3.4")->check(non_empty());
  g->add_option("--closed", o.closed, "The closed contacts, e.g. 2-3,3-4 (\"none\" for no closed contact)")->check(non_empty());
  g->add_flag("--all", o.all, "Every one of the 2^(n-1) cases");
  o.require_case = require_case;  // and at most one: the library's rules (resolve())
  cmd->add_option("--alphas", o.alphas_text, "The paper's couplings alpha_k in play (n = 4), e.g. 2 or 1,6")->check(non_empty());
  cmd->add_option("--coupling", o.coupling, "Couplings of pairs, e.g. 1-2/1-4,2-3/2-4, or near2")->check(non_empty());
  cmd->add_option("--pairs", o.pairs, std::string("Pairs with a diagonal K: all, near, near2 or a list 1-2,2-3; default ") + present::default_pairs)
      ->check(non_empty());
  // Not with --bodies, --alphas, --coupling or --pairs: the library's rule (SelectionOptions::check()).
  cmd->add_option("--scene", o.scene, "Take the pattern (declared entries of M) and n from a scene file (not with --bodies, --alphas, --coupling, --pairs)")
      ->check(non_empty());
  cmd->add_option("--obstacle", o.obstacle_text, "infinite (m_n = infinity, default) or finite (m_n a symbol; the m_n = infinity limit is also given)")
      ->capture_default_str();
  cmd->add_option("--scaling", o.scaling, "Orders in epsilon, e.g. m1=1,K14=-1 (default m1=1, K1n=-1, mn=-1 if finite; \"none\")")->check(non_empty());
  cmd->add_option("--order", o.order, "Correction orders kept beyond the dominant balance, 0 to " + std::to_string(present::max_order))
      ->capture_default_str();
}

}  // namespace superball::cli
