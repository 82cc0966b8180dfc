#include "anisodyn/analysis/dipolar_bonds.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "anisodyn/analysis/pair_search.hpp"
#include "anisodyn/core/error.hpp"
#include "anisodyn/interactions/dipolar_pair.hpp"

namespace anisodyn::analysis {

namespace {

/// InputError for a rule no bond could follow (its key, and the value that was given).
[[noreturn]] void bad_rule(const std::string& key, const std::string& problem, double value) {
  std::ostringstream o;
  o << problem << ", got " << value;
  throw InputError("", key, o.str());
}

}  // namespace

double dipolar_bond_cutoff(const DipolarBondRule& rule) {
  // βu ≥ −γ(σ/r)³ (θ = 0), so βu < βu_max < 0 needs r < σ (γ/|βu_max|)^{1/3}.
  return rule.sigma * std::cbrt(rule.gamma / std::abs(rule.bu_max));
}

std::vector<Bond> dipolar_bonds(const std::vector<Vec3>& positions, const Box& box, const DipolarBondRule& rule) {
  if (!(rule.bu_max < 0)) bad_rule("bu_max", "the bond threshold must be negative", rule.bu_max);
  if (!(rule.gamma > 0)) bad_rule("gamma", "the dipolar coupling must be positive", rule.gamma);
  std::vector<Bond> bonds;
  // a small margin: the strict test βu < βu_max decides, the cut-off only prunes
  for (const ClosePair& p : close_pairs(positions, box, dipolar_bond_cutoff(rule) * (1 + 1e-9)))
    if (dipolar_pair_energy(p.d, rule.field, rule.gamma, rule.sigma) < rule.bu_max) bonds.emplace_back(p.i, p.j);
  return bonds;
}

Components dipolar_clusters(const std::vector<Vec3>& positions, const Box& box, const DipolarBondRule& rule) {
  return connected_components(positions.size(), dipolar_bonds(positions, box, rule));
}

std::vector<char> dipolar_chain_mask(const std::vector<Vec3>& positions, const Box& box, const DipolarBondRule& rule) {
  const std::vector<std::size_t> size = dipolar_clusters(positions, box, rule).size_of_each();
  std::vector<char> mask(size.size());
  for (std::size_t i = 0; i < size.size(); ++i) mask[i] = size[i] >= 2;
  return mask;
}

DipolarBondRule parse_dipolar_bond_rule(tool::ConfigNode& cfg, bool with_threshold) {
  DipolarBondRule rule;
  rule.gamma = cfg.positive("gamma");
  rule.sigma = cfg.positive("sigma", 1.0);
  if (with_threshold) {
    rule.bu_max = cfg.number("bu_max", -3.20);
    if (!(rule.bu_max < 0)) cfg.fail("bu_max", "expected a negative bond energy threshold (kT)");
  }
  const Vec3 e = cfg.vec3("field_direction", Vec3::UnitZ());
  if (!(e.norm() > 0)) cfg.fail("field_direction", "expected a non-zero direction vector");
  rule.field = e.normalized();
  return rule;
}

}  // namespace anisodyn::analysis
