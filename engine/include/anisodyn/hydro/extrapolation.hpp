#pragma once
// Extrapolation of shell-model results to zero bead size. Each property is computed at several
// bead radii σ_b and a least-squares polynomial in σ_b is fitted through the values; its intercept
// is the σ_b → 0 limit. HYDRO++ (and spec 10 §8.4 step 5) fit a line; anisodyn-hydro can fit a
// line or a parabola (docs/hydro.md, "Extrapolation"), and uses the next higher fit as the check
// on the chosen one. The default, "auto", picks per body the fit whose own check is smaller.
#include <optional>
#include <string>
#include <vector>

namespace anisodyn::hydro {

/// The polynomial order of the fit whose intercept is reported.
enum class ExtrapolationOrder { Linear = 1, Quadratic = 2 };

/// What a run asks for (the key "extrapolation"): one fit, or Auto, which picks per body the fit
/// whose own error estimate is smaller (choose_extrapolation).
enum class ExtrapolationRule { Linear, Quadratic, Auto };

/// The extrapolation anisodyn-hydro uses unless told otherwise (docs/hydro.md, docs/decisions.md).
inline constexpr ExtrapolationRule kDefaultExtrapolation = ExtrapolationRule::Auto;

/// "linear" or "quadratic".
std::string extrapolation_name(ExtrapolationOrder order);
/// "linear", "quadratic" or "auto".
std::string extrapolation_name(ExtrapolationRule rule);

/// The auto rule. Arguments: each fit's error estimate (the largest relative estimate over the six
/// diagonals, DiffusionTensorResult::relative_error_of). Quadratic only when its estimate is
/// strictly smaller; a tie, or an estimate that is not a number, gives Linear (the simpler fit).
ExtrapolationOrder choose_extrapolation(double linear_error, double quadratic_error);

struct ZeroSizeExtrapolation {
  double linear = 0.0;     // intercept of the least-squares line through (σ_b, y)
  double slope = 0.0;
  double quadratic = 0.0;  // intercept of the least-squares parabola
  std::optional<double> cubic;  // intercept of the least-squares cubic; needs ≥ 4 distinct σ_b

  double intercept(ExtrapolationOrder order) const { return order == ExtrapolationOrder::Linear ? linear : quadratic; }
};

/// Needs at least three distinct σ_b (InputError otherwise).
ZeroSizeExtrapolation extrapolate_to_zero_size(const std::vector<double>& sigma_b, const std::vector<double>& y);

}  // namespace anisodyn::hydro
