"""Least-squares fits the report uses on measured scalars (values ± standard errors)."""
import math


class Line:
    """c0 + c1 x with the parameters' covariance, the reduced chi² and R²."""

    def __init__(self, c0, c1, cov, chi2, r2, points):
        self.c0, self.c1, self.cov, self.chi2, self.r2, self.points = c0, c1, cov, chi2, r2, points

    @property
    def c0_se(self):
        return math.sqrt(self.cov[0][0])

    @property
    def c1_se(self):
        return math.sqrt(self.cov[1][1])


def weighted_line(x, y, se):
    """The weighted least-squares line through (x, y) with weights 1/SE² (equal weights when an SE is
    missing or zero). The covariance is scaled by the reduced chi² when that exceeds 1, so scatter
    beyond the stated errors widens the parameters' errors; with two points the line goes through
    both and its errors come from theirs alone."""
    import numpy as np
    x, y, e = (np.asarray(v, dtype=float) for v in (x, y, se))
    if len(x) < 2 or len(set(x.tolist())) < 2:
        raise ValueError(f"a line needs two distinct x values, got {len(set(x.tolist()))}")
    weighted = bool(np.all(np.isfinite(e) & (e > 0)))
    w = 1.0 / e ** 2 if weighted else np.ones_like(x)
    A = np.vstack([np.ones_like(x), x]).T
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    c = cov @ (A.T @ (w * y))
    residual = y - A @ c
    dof = len(x) - 2
    chi2 = float(np.sum(w * residual ** 2) / dof) if dof > 0 else float("nan")
    if not weighted:  # no stated errors: the scatter alone sets them
        cov = cov * (chi2 if dof > 0 else float("nan"))
    elif dof > 0:
        cov = cov * max(1.0, chi2)
    spread = float(np.sum((y - y.mean()) ** 2))
    r2 = 1.0 - float(np.sum(residual ** 2)) / spread if spread > 0 else float("nan")
    return Line(float(c[0]), float(c[1]), cov.tolist(), chi2, r2, len(x))


def weighted_mean(values, se):
    """(mean, SE) with weights 1/SE² (the plain mean and its standard error when an SE is missing)."""
    import numpy as np
    v, e = np.asarray(values, dtype=float), np.asarray(se, dtype=float)
    if len(v) == 1:
        return float(v[0]), float(e[0])
    if np.all(np.isfinite(e) & (e > 0)):
        w = 1.0 / e ** 2
        return float(np.sum(w * v) / np.sum(w)), float(1.0 / math.sqrt(np.sum(w)))
    return float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))
