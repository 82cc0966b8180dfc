#include "anisodyn/hydro/extrapolation.hpp"

#include <Eigen/Dense>
#include <set>

#include "anisodyn/core/error.hpp"

namespace anisodyn::hydro {

namespace {
Eigen::VectorXd polynomial_fit(const std::vector<double>& x, const std::vector<double>& y, int degree) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(x.size()), degree + 1);
  Eigen::VectorXd b(static_cast<Eigen::Index>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    for (int p = 0; p <= degree; ++p) A(r, p) = std::pow(x[i], p);
    b(r) = y[i];
  }
  return A.colPivHouseholderQr().solve(b);
}
}  // namespace

ZeroSizeExtrapolation extrapolate_to_zero_size(const std::vector<double>& sigma_b, const std::vector<double>& y) {
  if (sigma_b.size() != y.size()) throw InputError("extrapolation: one value per bead radius expected");
  if (std::set<double>(sigma_b.begin(), sigma_b.end()).size() < 3)
    throw InputError("extrapolation to zero bead size needs at least three distinct bead radii");
  const Eigen::VectorXd line = polynomial_fit(sigma_b, y, 1);
  const Eigen::VectorXd parabola = polynomial_fit(sigma_b, y, 2);
  return {line(0), line(1), parabola(0)};
}

}  // namespace anisodyn::hydro
