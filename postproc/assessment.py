"""Statistics of a launch sweep (issue 16): how sure a verdict drawn from a finite number of
launches is.

wilson_interval: the score interval of a binomial proportion (Wilson 1927, without
continuity correction; Newcombe 1998, Stat Med 17:857, method 3). It stays inside [0, 1]
and is not degenerate at k = 0 or k = n, which matters here: most cells of a sweep have
no collision at all, and "0 of 20" must still read "up to 16 %".

launches_needed: how many further failure-free launches bring the Wilson upper bound
below a risk level, solved from the same formula.

fit_gumbel: the type I (largest) extreme-value law fitted to per-launch maxima by maximum
likelihood (the method of moments as its start), with its most probable maximum, its
fractiles and a stated goodness-of-fit check (probability-plot correlation coefficient
against a Monte Carlo critical value, and the Anderson-Darling statistic against Stephens'
critical value), so a fractile is never quoted from a law that does not fit.

numpy and the standard library only (no scipy): the normal quantile is Acklam's rational
approximation polished by one Halley step on math.erfc (relative error ~1e-15).
"""
import math
from dataclasses import dataclass

import numpy as np

EULER_GAMMA = 0.5772156649015329
# asymptotic variances of the Gumbel MLE, in units of beta^2/n: var(mu) = 1 + 6(1 -
# gamma)^2/pi^2 = 1.1087, var(beta) = 6/pi^2 = 0.6079
GUMBEL_VAR_MU = 1.1087
GUMBEL_VAR_BETA = 0.6079
# Anderson-Darling, Gumbel (largest) with both parameters estimated: the modified statistic
# A2* = A2 (1 + 0.2/sqrt(n)) against 0.757 at the 5 % level (Stephens 1977; D'Agostino &
# Stephens 1986, Goodness-of-Fit Techniques, Table 4.17)
AD_CRITICAL_5 = 0.757
PPCC_SIMULATIONS = 2000
PPCC_SEED = 19860401          # fixed: the critical value of a sample size is reproducible
MIN_FIT_SAMPLES = 3

_A = (-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
      1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00)
_B = (-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
      6.680131188771972e+01, -1.328068155288572e+01)
_C = (-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
      -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00)
_D = (7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
      3.754408661907416e+00)


def _poly(coefficients, x):
    """Horner's rule, highest power first."""
    out = 0.0
    for c in coefficients:
        out = out * x + c
    return out


def normal_quantile(p):
    """The standard normal quantile z(p), 0 < p < 1: Acklam's algorithm, whose ~1e-9
    error one Halley step on the exact CDF (math.erfc) removes; the upper half by
    symmetry."""
    if not 0.0 < p < 1.0:
        raise ValueError(f"normal_quantile: p = {p} is not in (0, 1)")
    if p > 0.5:
        return -normal_quantile(1 - p)      # the Halley step is exact in the lower tail
    low = 0.02425
    if p < low:
        q = math.sqrt(-2 * math.log(p))
        x = _poly(_C, q) / (_poly(_D, q) * q + 1)
    else:
        q = p - 0.5
        r = q * q
        x = _poly(_A, r) * q / (_poly(_B, r) * r + 1)
    e = 0.5 * math.erfc(-x / math.sqrt(2)) - p
    u = e * math.sqrt(2 * math.pi) * math.exp(x * x / 2)
    return x - u / (1 + x * u / 2)


def _z(confidence):
    """Two-sided critical value of the normal law for `confidence` (0.95 -> 1.95996)."""
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence = {confidence} is not in (0, 1)")
    return normal_quantile(1 - (1 - confidence) / 2)


def wilson_interval(k, n, confidence=0.95):
    """(lower, upper) Wilson score interval of k successes in n trials, without continuity
    correction; n = 0 says nothing: (0, 1)."""
    k, n = int(k), int(n)
    if n < 0 or not 0 <= k <= n:
        raise ValueError(f"wilson_interval: k = {k}, n = {n}")
    if n == 0:
        return 0.0, 1.0
    z2 = _z(confidence) ** 2
    p = k / n
    centre = (p + z2 / (2 * n)) / (1 + z2 / n)
    half = math.sqrt(z2) / (1 + z2 / n) * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n))
    lower = 0.0 if k == 0 else max(0.0, centre - half)
    upper = 1.0 if k == n else min(1.0, centre + half)
    return lower, upper


def launches_needed(k, n, risk, confidence=0.95):
    """How many further failure-free launches bring the Wilson upper bound of k failures in
    n launches to <= risk (0 if it already is). With N = n + m launches the upper bound is
    <= r exactly when k/N <= r and (rN - k)^2 >= z^2 r(1 - r) N: N at or beyond the larger
    root of r^2 N^2 - (2kr + z^2 r(1 - r)) N + k^2 = 0. The root is checked (and nudged by
    the odd launch rounding may cost) against wilson_interval itself."""
    if not 0.0 < risk < 1.0:
        raise ValueError(f"launches_needed: risk = {risk} is not in (0, 1)")
    z2 = _z(confidence) ** 2
    b = 2 * k * risk + z2 * risk * (1 - risk)
    root = (b + math.sqrt(max(b * b - 4 * risk * risk * k * k, 0.0))) / (2 * risk * risk)
    total = max(int(n), math.ceil(root) - 1, 1)
    while wilson_interval(k, total, confidence)[1] > risk:
        total += 1
    while total > max(int(n), 1) and wilson_interval(k, total - 1, confidence)[1] <= risk:
        total -= 1
    return total - int(n)


# --- Gumbel (type I largest) ---------------------------------------------------------------

@dataclass(frozen=True)
class GumbelFit:
    """A Gumbel law F(x) = exp(-exp(-(x - mu)/beta)) fitted to n maxima, with its check.

    se_mu, se_beta: asymptotic MLE standard errors sqrt(1.1087/n) beta, sqrt(0.6079/n) beta.
    ppcc: correlation of the sorted sample with the Gumbel quantiles at Gringorten's plotting
    positions (i - 0.44)/(n + 0.12); ppcc_critical: its 5 % point for this n, by Monte
    Carlo (PPCC_SIMULATIONS samples of size n drawn, with the fixed seed PPCC_SEED, from the
    fitted law itself; the PPCC does not depend on mu and beta, so this is the null
    distribution of the test). Vogel's (1986) table is not used: its values could not be
    confirmed here. ad: Anderson-Darling A2 against the fitted law; ad_star = A2 (1 +
    0.2/sqrt(n)) is compared with 0.757 (5 %, both parameters estimated: Stephens 1977).
    fits: both tests accept at 5 % (together a false alarm at most ~10 % of the time: a
    designer is warned rather than reassured)."""
    n: int
    mu: float
    beta: float
    se_mu: float
    se_beta: float
    ppcc: float
    ppcc_critical: float
    ad: float
    ad_star: float
    ad_critical: float = AD_CRITICAL_5

    @property
    def mpm(self):
        """Most probable maximum: the mode of the law, mu."""
        return self.mu

    def fractile(self, p):
        """The value not exceeded with probability p: mu - beta ln(-ln p)."""
        return self.mu - self.beta * math.log(-math.log(p))

    @property
    def p90(self):
        """The 90 % fractile."""
        return self.fractile(0.9)

    @property
    def ppcc_ok(self):
        return self.ppcc >= self.ppcc_critical

    @property
    def ad_ok(self):
        return self.ad_star <= self.ad_critical

    @property
    def fits(self):
        return self.ppcc_ok and self.ad_ok


def gumbel_moments(x):
    """(mu, beta) by the method of moments: beta = s sqrt(6)/pi, mu = mean - gamma beta."""
    x = np.asarray(x, dtype=float)
    beta = np.std(x, ddof=1) * math.sqrt(6) / math.pi
    return float(np.mean(x) - EULER_GAMMA * beta), float(beta)


def _scale_equation(beta, y):
    """The MLE's scale equation g(beta) = beta - mean(y) + sum(y w)/sum(w), w = exp(-y/beta),
    and g'(beta) = 1 + var_w(y)/beta^2 > 0 (so its root is unique); y is shifted to min 0,
    which leaves g unchanged and keeps the weights in (0, 1]."""
    w = np.exp(-y / beta)
    sw = w.sum()
    mean_w = (y * w).sum() / sw
    var_w = ((y - mean_w) ** 2 * w).sum() / sw
    return beta - y.mean() + mean_w, 1 + var_w / beta ** 2


def gumbel_mle(x, tol=1e-12, max_iter=200):
    """(mu, beta) by maximum likelihood: Newton on the scale equation from the moments'
    beta, falling back to bisection whenever a step leaves the bracket; then mu = -beta
    ln(mean(exp(-x/beta)))."""
    x = np.asarray(x, dtype=float)
    xmin = x.min()
    y = x - xmin
    _, beta = gumbel_moments(x)
    lo, hi = 1e-12 * max(y.max(), 1e-300), 2 * y.max() + beta
    for _ in range(max_iter):
        g, dg = _scale_equation(beta, y)
        if g > 0:
            hi = beta
        else:
            lo = beta
        step = beta - g / dg
        new = step if lo < step < hi else 0.5 * (lo + hi)
        if abs(new - beta) <= tol * beta:
            beta = new
            break
        beta = new
    mu = xmin - beta * math.log(np.mean(np.exp(-y / beta)))
    return float(mu), float(beta)


def gringorten_quantiles(n):
    """Standard Gumbel quantiles -ln(-ln p_i) at Gringorten's p_i = (i - 0.44)/(n + 0.12)."""
    p = (np.arange(1, n + 1) - 0.44) / (n + 0.12)
    return -np.log(-np.log(p))


def _ppcc(sorted_x, q):
    """Correlation of sorted samples (last axis) with the plotting quantiles q."""
    xc = sorted_x - sorted_x.mean(axis=-1, keepdims=True)
    qc = q - q.mean()
    return (xc @ qc) / np.sqrt((xc ** 2).sum(axis=-1) * (qc ** 2).sum())


def ppcc_critical(n, mu=0.0, beta=1.0, level=0.05, simulations=PPCC_SIMULATIONS,
                  seed=PPCC_SEED):
    """The `level` point of the Gumbel PPCC for samples of size n, by Monte Carlo from the
    law (mu, beta) with a fixed seed."""
    rng = np.random.default_rng(seed)
    samples = np.sort(rng.gumbel(mu, beta, size=(simulations, n)), axis=1)
    return float(np.quantile(_ppcc(samples, gringorten_quantiles(n)), level))


def anderson_darling(x, mu, beta):
    """A2 = -n - (1/n) sum (2i - 1)[ln F(x_i) + ln(1 - F(x_(n+1-i)))] of the sorted sample
    against the Gumbel law (mu, beta); ln(1 - F) through expm1, exact in the upper tail."""
    x = np.sort(np.asarray(x, dtype=float))
    n = x.size
    e = np.exp(-(x - mu) / beta)
    log_f = -e
    log_sf = np.log(-np.expm1(-e))
    i = np.arange(1, n + 1)
    return float(-n - np.sum((2 * i - 1) * (log_f + log_sf[::-1])) / n)


def fit_gumbel(x, simulations=PPCC_SIMULATIONS):
    """GumbelFit of the finite values of x; None for fewer than MIN_FIT_SAMPLES of them or
    no spread (a law cannot be told from so little)."""
    x = np.asarray(x, dtype=float)
    x = x[np.isfinite(x)]
    n = x.size
    if n < MIN_FIT_SAMPLES or np.ptp(x) <= 0:
        return None
    mu, beta = gumbel_mle(x)
    ad = anderson_darling(x, mu, beta)
    return GumbelFit(n=n, mu=mu, beta=beta, se_mu=math.sqrt(GUMBEL_VAR_MU / n) * beta,
                     se_beta=math.sqrt(GUMBEL_VAR_BETA / n) * beta,
                     ppcc=float(_ppcc(np.sort(x), gringorten_quantiles(n))),
                     ppcc_critical=ppcc_critical(n, mu, beta, simulations=simulations),
                     ad=ad, ad_star=ad * (1 + 0.2 / math.sqrt(n)))
