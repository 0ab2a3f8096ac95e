// The rules of the options of verify_case(), audit_paper(),
// explore_case() and the paper's reproduction, and the parsing of their text forms: the one place where
// the command and the Python module learn what a bad value is.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "superball/cases/error.hpp"
#include "superball/cases/number.hpp"
#include "superball/numeric/parallel.hpp"
#include "superball/numeric/scalar.hpp"
#include "superball/verify/audit.hpp"
#include "superball/verify/explore.hpp"
#include "superball/verify/reproduce.hpp"
#include "superball/verify/verification.hpp"

namespace superball::verify {
namespace {

/// "NAME must be a whole number from LOW to HIGH, got VALUE" unless low <= value <= high.
void check_whole(const char* function, const char* name, int value, int low, int high) {
  if (value < low || value > high)
    throw std::invalid_argument(std::string(function) + "(): " + name + " must be a whole number from " + std::to_string(low) + " to " +
                                std::to_string(high) + ", got " + std::to_string(value));
}

/// "NAME must be in (0, 1), got VALUE" unless 0 < epsilon < 1.
void check_epsilon(const char* function, const char* name, const cln::cl_RA& epsilon) {
  if (!(epsilon > 0) || !(epsilon < 1))
    throw std::invalid_argument(std::string(function) + "(): " + name + " must be in (0, 1), got " + numeric::to_string(epsilon));
}

}  // namespace

cln::cl_RA parse_epsilon(const std::string& option, const std::string& text) {
  try {
    return numeric::parse_rational(Number::parse(text).fraction());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("parse_epsilon(): " + option + ": '" + text + "': " + without_function_prefix(e.what()));
  }
}

std::vector<cln::cl_RA> parse_epsilons(const std::string& text) {
  std::vector<cln::cl_RA> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(parse_epsilon("epsilons", item));
  if (out.empty()) throw std::invalid_argument("parse_epsilons(): epsilons: no value (e.g. 1e-2,1e-4)");
  return out;
}

void VerifyOptions::check() const {
  if (epsilons.empty()) throw std::invalid_argument("VerifyOptions::check(): epsilons: no value (e.g. 1e-2,1e-4)");
  for (const cln::cl_RA& e : epsilons) check_epsilon("VerifyOptions::check", "epsilons", e);
  check_whole("VerifyOptions::check", "samples", samples, 1, max_verify_samples);
  check_whole("VerifyOptions::check", "boundary_pairs", boundary_pairs, 0, max_boundary_pairs);
  numeric::check_threads(threads);
}

void AuditOptions::check() const {
  check_epsilon("AuditOptions::check", "epsilon", epsilon);
  check_whole("AuditOptions::check", "samples", samples, 1, max_audit_samples);
}

void ExploreOptions::check() const {
  check_whole("ExploreOptions::check", "starts", starts, 1, max_starts);
  check_whole("ExploreOptions::check", "evaluations", evaluations, 10, max_evaluations);
  if (!(box_low > 0) || !(box_high > box_low) || !std::isnormal(box_low) || !std::isnormal(box_high))
    throw std::invalid_argument("ExploreOptions::check(): box " + numeric::to_string(box_low, 6) + ":" + numeric::to_string(box_high, 6) +
                                ": needs 0 < LOW < HIGH with LOW >= " + numeric::to_string(std::numeric_limits<double>::min(), 17) +
                                " and HIGH finite (normal doubles)");
}

void ReproduceOptions::check() const {
  check_whole("ReproduceOptions::check", "samples", samples, 1, max_audit_samples);
  check_whole("ReproduceOptions::check", "verify_samples", verify_samples, 1, max_verify_samples);
  check_whole("ReproduceOptions::check", "explore_starts", explore_starts, 1, max_starts);
  numeric::check_threads(threads);
}

AuditOptions ReproduceOptions::audit() const {
  AuditOptions options;
  options.samples = samples;
  return options;
}

VerifyOptions ReproduceOptions::verification() const {
  VerifyOptions options;
  options.samples = verify_samples;
  options.threads = threads;
  return options;
}

ExploreOptions ReproduceOptions::exploration() const {
  ExploreOptions options;
  options.starts = explore_starts;
  return options;
}

std::pair<double, double> parse_box(const std::string& text) {
  const std::string bad = "parse_box(): box: '" + text + "' is not LOW:HIGH (e.g. 1e-3:1e3)";
  const std::size_t colon = text.find(':');
  auto number = [&](const std::string& s) {
    char* end = nullptr;
    const double v = s.empty() || std::isspace(static_cast<unsigned char>(s[0])) ? 0 : std::strtod(s.c_str(), &end);
    if (!end || end != s.c_str() + s.size()) throw std::invalid_argument(bad);
    return v;
  };
  if (colon == std::string::npos) throw std::invalid_argument(bad);
  return {number(text.substr(0, colon)), number(text.substr(colon + 1))};
}

}  // namespace superball::verify
