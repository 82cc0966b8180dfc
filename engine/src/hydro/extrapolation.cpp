#include "anisodyn/hydro/extrapolation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>

#include "anisodyn/core/error.hpp"

namespace anisodyn::hydro {

namespace {
/// Least-squares coefficients c_0 … c_degree of y ≈ Σ c_p x^p. The fit runs in u = x/max|x|, so
/// that the columns of the design matrix are of order one, and the coefficients are scaled back.
Eigen::VectorXd polynomial_fit(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  double scale = 0.0;
  for (double v : x) scale = std::max(scale, std::abs(v));
  if (!(scale > 0.0)) scale = 1.0;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(x.size()), degree + 1);
  Eigen::VectorXd b(static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    for (int p = 0; p <= degree; ++p) A(r, p) = std::pow(x[i] / scale, p);
    b(r) = y[i];
  }
  Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  for (int p = 1; p <= degree; ++p) c(p) /= std::pow(scale, p);
  return c;
}
}  // namespace

std::string extrapolation_name(ExtrapolationOrder order) {
  return order == ExtrapolationOrder::Linear ? "linear" : "quadratic";
}

std::string extrapolation_name(ExtrapolationRule rule) {
  switch (rule) {
    case ExtrapolationRule::Linear: return extrapolation_name(ExtrapolationOrder::Linear);
    case ExtrapolationRule::Quadratic: return extrapolation_name(ExtrapolationOrder::Quadratic);
    case ExtrapolationRule::Auto: break;
  }
  return "auto";
}

ExtrapolationOrder choose_extrapolation(double linear_error, double quadratic_error) {
  return quadratic_error < linear_error ? ExtrapolationOrder::Quadratic : ExtrapolationOrder::Linear;
}

ZeroSizeExtrapolation extrapolate_to_zero_size(const std::vector<double>& sigma_b, const std::vector<double>& y) {
  if (sigma_b.size() != y.size()) throw InputError("extrapolation: one value per bead radius expected");
  const std::size_t distinct = std::set<double>(sigma_b.begin(), sigma_b.end()).size();
  if (distinct < 3) throw InputError("extrapolation to zero bead size needs at least three distinct bead radii");
  const Eigen::VectorXd line = polynomial_fit(sigma_b, y, 1);
  const Eigen::VectorXd parabola = polynomial_fit(sigma_b, y, 2);
  ZeroSizeExtrapolation out{line(0), line(1), parabola(0), std::nullopt};
  if (distinct >= 4) out.cubic = polynomial_fit(sigma_b, y, 3)(0);
  return out;
}

}  // namespace anisodyn::hydro
