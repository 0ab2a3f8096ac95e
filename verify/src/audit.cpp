#include "superball/verify/audit.hpp"

#include <cln/rational_io.h>
#include <ginac/ginac.h>

#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>

#include "superball/cases/vocabulary.hpp"
#include "superball/numeric/collision.hpp"
#include "superball/numeric/problem.hpp"
#include "superball/symbolic/derivation.hpp"
#include "superball/symbolic/format.hpp"
#include "superball/verify/explore.hpp"

namespace superball::verify {
namespace detail {

using cln::cl_RA;
using namespace superball::symbolic;

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("audit_paper(): " + what); }

/// A formula printed by \p print in both notations.
template <class Print>
Formula both(const Print& print) {
  return {print(Style::Text), print(Style::Latex)};
}

std::string where(const PrintedCondition& c) { return "§" + c.section + " case " + c.case_name + " " + c.kind + " " + c.about; }

/// The substitution symbol → value of the point \p x.
GiNaC::exmap substitution(const Symbols& s, const Point& x) {
  GiNaC::exmap m;
  for (std::size_t k = 0; k < x.size(); ++k) m[s.all()[k].symbol] = GiNaC::numeric(cln::cl_N(x[k]));
  return m;
}

/// Whether the polynomial \p p is > 0 (strict) or >= 0 at \p x.
bool holds(const Polynomial& p, const Point& x, bool strict) {
  const cl_RA v = p(x);
  return strict ? cln::plusp(v) : !cln::minusp(v);
}

ConditionKind kind_of(const std::string& kind, const std::string& context) {
  for (ConditionKind k : {ConditionKind::Superball, ConditionKind::Evolution, ConditionKind::Contact, ConditionKind::Psd})
    if (kind == to_string(k)) return k;
  fail(context + ": unknown condition kind '" + kind + "'");
}

const Condition* find(const Derivation& d, const std::string& kind, const std::string& about) {
  for (const Condition& c : d.conditions)
    if (to_string(c.kind) == kind && c.about == about) return &c;
  return nullptr;
}

GiNaC::ex parse(const Symbols& s, const std::string& text, const std::string& context) {
  try {
    GiNaC::parser reader(s.table(), true);
    return reader(text);
  } catch (const std::exception& e) {
    fail(context + ": cannot read '" + text + "': " + e.what());
  }
}

ContactSet named_case(const std::string& name, const std::string& context) {
  try {
    return Vocabulary::paper().named_case(name).closed;
  } catch (const std::invalid_argument&) {
    fail(context + ": no case '" + name + "'");
  }
}

std::string ascii(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

/// Deriver and derivations per pattern, shared by the entries.
class Cache {
 public:
  const Deriver& deriver(const std::vector<int>& alphas) {
    auto& slot = derivers_[alphas];
    if (!slot) slot = std::make_unique<Deriver>(Pattern::paper(alphas), Obstacle::Infinite);
    return *slot;
  }
  const ParameterSpace& space(const std::vector<int>& alphas) {
    auto& slot = spaces_[alphas];
    if (!slot) slot = std::make_unique<ParameterSpace>(deriver(alphas));
    return *slot;
  }
  const Derivation& derivation(const std::vector<int>& alphas, const ContactSet& closed) {
    const auto key = std::make_pair(alphas, closed.to_string());
    auto it = derivations_.find(key);
    if (it == derivations_.end()) it = derivations_.emplace(key, deriver(alphas).derive(closed)).first;
    return it->second;
  }

 private:
  std::map<std::vector<int>, std::unique_ptr<Deriver>> derivers_;
  std::map<std::vector<int>, std::unique_ptr<ParameterSpace>> spaces_;
  std::map<std::pair<std::vector<int>, std::string>, Derivation> derivations_;
};

ConditionAudit audit_condition(const PrintedCondition& pc, const AuditOptions& o, Cache& cache, std::uint64_t seed) {
  const std::string ctx = where(pc);
  ConditionAudit out;
  out.printed = pc;
  if (!pc.note.empty()) out.notes.push_back("transcription: " + pc.note);
  const Deriver& deriver = cache.deriver(pc.alphas);
  const Symbols& s = deriver.symbols();
  const Derivation& d = cache.derivation(pc.alphas, named_case(pc.case_name, ctx));
  const GiNaC::ex rhs = parse(s, pc.rhs, ctx);
  if (pc.kind == "velocity") {
    if (pc.lhs.size() < 2 || pc.lhs[0] != 'U') fail(ctx + ": a velocity formula reads U<i> = ...");
    const int body = std::stoi(pc.lhs.substr(1));
    if (body < 1 || body > s.bodies()) fail(ctx + ": no body " + pc.lhs.substr(1));
    const Fraction& u = d.velocities[static_cast<std::size_t>(body - 1)];
    const GiNaC::ex nd = GiNaC::numer_denom(rhs);
    const Fraction as_printed{nd.op(0), nd.op(1)};
    auto velocity = [&](const Fraction& f) {
      return both([&](Style style) { return velocity_name(body, style) + " = " + format_fraction(f, s, style); });
    };
    out.title = {"velocity " + velocity_name(body, Style::Text), "velocity $" + velocity_name(body, Style::Latex) + "$"};
    out.as_printed = velocity(as_printed);
    out.exact = out.asymptotic = velocity(u);
    out.agreement = GiNaC::normal(u.value() - rhs).is_zero() ? Agreement::IdenticalExact : Agreement::Different;
    if (out.agreement == Agreement::Different) {
      const ParameterSpace& space = cache.space(pc.alphas);
      RegimeSampler sampler(space, o.epsilon, seed);
      numeric::CollisionSolver<cl_RA> solver;
      for (out.tried = 0; out.tried < o.samples && !out.witness; ++out.tried) {
        const auto x = sampler.draw();
        if (!x) break;
        numeric::Solution<cl_RA> sol;
        solver.compute_case(space.problem(*x), d.closed, sol);
        const GiNaC::ex printed = rhs.subs(substitution(s, *x), GiNaC::subs_options::no_pattern);
        if (!printed.is_equal(GiNaC::numeric(cln::cl_N(sol.velocities_after[static_cast<std::size_t>(body - 1)])))) {
          Witness w;
          w.point = space.named(*x);
          w.quantity = pc.lhs + " = " + to_string(sol.velocities_after[static_cast<std::size_t>(body - 1)]) + ", printed formula gives " + ascii(printed);
          w.numeric = true;
          w.derived_exact = w.derived_asymptotic = true;
          out.witness = w;
        }
      }
    }
    return out;
  }
  const GiNaC::ex lhs = parse(s, pc.lhs, ctx);
  const bool greater = pc.relation == ">" || pc.relation == ">=";
  const bool strict = pc.relation == ">" || pc.relation == "<";
  const GiNaC::ex q = GiNaC::expand(greater ? lhs - rhs : rhs - lhs);
  const Relation rel = strict ? Relation::Greater : Relation::GreaterEqual;
  const Condition* c = find(d, pc.kind, pc.about);
  if (!c) fail(ctx + ": the case has no " + pc.kind + " condition about " + pc.about);
  out.title = both([&](Style style) { return condition_title(*c, style); });
  out.as_printed = both([&](Style style) { return format_condition(q, rel, s, style); });
  out.exact = both([&](Style style) { return format_condition(c->exact, c->relation, s, style); });
  out.asymptotic = both([&](Style style) { return format_condition(c->asymptotic, c->relation, s, style); });
  GiNaC::numeric printed_order;
  const GiNaC::ex q_asymptotic = deriver.asymptotic(q, &printed_order);
  out.printed_asymptotic = both([&](Style style) { return format_condition(q_asymptotic, rel, s, style); });
  if (same_condition(q, c->exact.numerator, s))
    out.agreement = Agreement::IdenticalExact;
  else if (same_condition(q_asymptotic, c->asymptotic.numerator, s))
    out.agreement = Agreement::IdenticalAsymptotic;
  else
    out.agreement = Agreement::Different;
  if (out.agreement != Agreement::Different && (rel != c->relation))
    out.notes.push_back(std::string("the printed relation is ") + (strict ? "strict" : "not strict") + ", the derived one " +
                        (c->relation == Relation::Greater ? "strict" : "not strict") + " (they differ only on the boundary)");
  for (const Condition& m : deriver.psd())
    if (m.about.find(',') != std::string::npos && same_condition(q, m.exact.numerator, s))
      out.notes.push_back("the printed condition is the positive semi-definiteness minor of M on " + m.about + ": it holds at every admissible point");
  if (out.agreement != Agreement::Different) return out;

  // A point where the printed condition and the exact solution disagree; prefer one where the
  // derived asymptotic condition agrees too (the derived exact one always does).
  const ParameterSpace& space = cache.space(pc.alphas);
  const Polynomial printed_poly(q, s);
  const CompiledCondition exact(*c, c->exact, s), asymptotic(*c, c->asymptotic, s);
  RegimeSampler sampler(space, o.epsilon, seed);
  numeric::CollisionSolver<cl_RA> solver;
  for (out.tried = 0; out.tried < o.samples; ++out.tried) {
    const auto x = sampler.draw();
    if (!x) break;
    const numeric::Problem<cl_RA> problem = space.problem(*x);
    numeric::Solution<cl_RA> sol;
    solver.compute_case(problem, d.closed, sol);
    if (sol.status != numeric::Status::Success) continue;
    Witness w;
    w.numeric = condition_truth(kind_of(pc.kind, ctx), pc.about, problem, sol, &w.quantity);
    w.printed = holds(printed_poly, *x, strict);
    if (w.printed == w.numeric) continue;
    w.derived_exact = exact.holds(*x);
    w.derived_asymptotic = asymptotic.holds(*x);
    w.point = space.named(*x);
    numeric::Solution<cl_RA> actual;
    solver.compute(problem, actual);
    w.actual_case = Vocabulary::paper().case_name(actual.closed);
    const bool best = w.derived_exact == w.numeric && w.derived_asymptotic == w.numeric;
    if (!out.witness || best) out.witness = w;
    if (best) {
      ++out.tried;
      break;
    }
  }
  return out;
}

/// Rename α_like → α_claim in the ASCII printing of \p e and read it in \p target's symbols.
GiNaC::ex renamed(const GiNaC::ex& e, const std::vector<int>& from, const std::vector<int>& to, const Symbols& target) {
  std::string text = ascii(e);
  for (std::size_t k = 0; k < from.size() && k < to.size(); ++k) {
    const std::string a = "alpha" + std::to_string(from[k]), b = "alpha" + std::to_string(to[k]);
    for (std::size_t at = text.find(a); at != std::string::npos; at = text.find(a, at + b.size())) text.replace(at, a.size(), b);
  }
  GiNaC::parser reader(target.table(), true);
  return reader(text);
}

ClaimAudit audit_claim(const PaperClaim& pc, const AuditOptions& o, Cache& cache, std::uint64_t seed) {
  ClaimAudit out;
  out.claim = pc;
  const std::string ctx = "claim " + pc.id;
  const ContactSet closed = named_case(pc.case_name, ctx);
  const Deriver& deriver = cache.deriver(pc.alphas);
  const Symbols& s = deriver.symbols();
  const Derivation& d = cache.derivation(pc.alphas, closed);
  const Condition* superball = find(d, "superball", "U1 > a");
  out.superball = both([&](Style style) { return format_condition(superball->exact, superball->relation, s, style); });
  if (!pc.like.empty()) {
    const Derivation& like = cache.derivation(pc.like, closed);
    for (const Condition& c : d.conditions) {
      if (c.kind == ConditionKind::Psd) continue;
      const Condition* other = find(like, to_string(c.kind), c.about);
      if (!other) continue;
      const GiNaC::ex mapped = renamed(other->exact.numerator, pc.like, pc.alphas, s);
      const GiNaC::ex mapped_as = renamed(other->asymptotic.numerator, pc.like, pc.alphas, s);
      std::string line = std::string(to_string(c.kind)) + " " + c.about + ": ";
      if (same_condition(mapped, c.exact.numerator, s))
        line += "identical to the other pattern's exact condition after renaming";
      else if (same_condition(mapped_as, c.asymptotic.numerator, s))
        line += "identical at the asymptotic order after renaming (" + format_condition(c.asymptotic, c.relation, s, Style::Text) + ")";
      else
        line += "different: " + format_condition(c.asymptotic, c.relation, s, Style::Text) + " here, " +
                format_condition(mapped_as, other->relation, s, Style::Text) + " renamed from the other pattern (asymptotic forms)";
      out.comparisons.push_back(line);
    }
  }
  if (pc.claim == "superball impossible") out.certificate = impossibility_certificate(superball->exact.numerator, s);
  // Points where the case is the actual evolution and U1 > a.
  const ParameterSpace& space = cache.space(pc.alphas);
  const CompiledCondition exact(*superball, superball->exact, s), asymptotic(*superball, superball->asymptotic, s);
  RegimeSampler sampler(space, o.epsilon, seed);
  numeric::CollisionSolver<cl_RA> solver;
  for (out.tried = 0; out.tried < o.samples; ++out.tried) {
    const auto x = sampler.draw();
    if (!x) break;
    const numeric::Problem<cl_RA> problem = space.problem(*x);
    numeric::Solution<cl_RA> sol;
    solver.compute(problem, sol);
    if (sol.status != numeric::Status::Success || sol.closed != closed) continue;
    const cl_RA a = -problem.u.front();
    if (!(sol.velocities_after[0] > a)) continue;
    ++out.hits;
    if (!out.example) {
      Witness w;
      w.point = space.named(*x);
      w.quantity = "U1 = " + to_string(sol.velocities_after[0]) + ", a = " + to_string(a);
      w.actual_case = Vocabulary::paper().case_name(sol.closed);
      w.numeric = true;
      w.derived_exact = exact.holds(*x);
      w.derived_asymptotic = asymptotic.holds(*x);
      out.example = w;
    }
    if (pc.claim == "superball possible") {
      ++out.tried;
      break;
    }
  }
  if (pc.claim == "superball possible") {
    out.supported = out.example.has_value();
    out.verdict = out.supported ? "supported: a point where case " + pc.case_name + " is the actual evolution and U1+ > a"
                                : "not confirmed: no point with case " + pc.case_name + " actual and U1+ > a in " + std::to_string(out.tried) + " samples";
  } else {
    out.supported = !out.certificate.empty() && out.hits == 0;
    out.verdict = !out.certificate.empty() ? "proved: U1+ > a is impossible in case " + pc.case_name + " for every M positive semi-definite"
                                           : (out.hits ? "refuted: " + std::to_string(out.hits) + " sampled points have case " + pc.case_name + " actual and U1+ > a"
                                                       : "not proved (no certificate); no counter-example in " + std::to_string(out.tried) + " samples");
  }
  return out;
}

}  // namespace detail

const char* to_string(Agreement a) {
  switch (a) {
    case Agreement::IdenticalExact: return "identical to the exact condition";
    case Agreement::IdenticalAsymptotic: return "identical at the asymptotic order";
    case Agreement::Different: break;
  }
  return "different";
}

Audit audit_paper(const PrintedConditions& data, const AuditOptions& options) {
  options.check();
  Audit audit;
  audit.options = options;
  detail::Cache cache;
  std::uint64_t seed = options.seed;
  for (const PrintedCondition& c : data.conditions) audit.conditions.push_back(detail::audit_condition(c, options, cache, seed++));
  for (const PaperClaim& c : data.claims) audit.claims.push_back(detail::audit_claim(c, options, cache, seed++));
  return audit;
}

}  // namespace superball::verify
