//! The statistics of a calibrated robot's drift check (`calibrate --update`): how many check
//! readings an undrifted robot puts beyond the calibration's held-out error bound, and the least
//! bound the tracker's noise allows.
//!
//! The bound is a split conformal quantile at `level` of the calibration's held-out error
//! lengths: a reading of the undrifted robot lies beyond it with probability at most
//! `1 - level`, so the count of `n` check readings beyond it is at most binomial
//! `(n, 1 - level)` ([`allowed`], a one-sided binomial test). The bound is never below what the
//! tracker's noise alone makes of a reading's error length ([`noise_length`]).

/// The length (m) below which the 3D error of a reading with `noise` per coordinate (m, Gaussian)
/// lies at `level` (in (0, 1)): `noise sqrt(q_3(level))` (module docs); 0 without noise.
pub fn noise_length(noise: f64, level: f64) -> f64 {
    use statrs::distribution::{ChiSquared, ContinuousCDF};
    match ChiSquared::new(3.0) {
        Ok(chi) if noise > 0.0 => noise * chi.inverse_cdf(level).sqrt(),
        _ => 0.0,
    }
}

/// The largest count `k` of `n` trials of probability `p` with `P(X > k) > alpha` no more:
/// the smallest `k` with `P(X >= k + 1) <= alpha` (binomial, the probabilities summed in
/// log space so that no term underflows the sum's start); 0 when `p <= 0`, `n` when no count
/// below `n` reaches `alpha`.
pub fn allowed(n: usize, p: f64, alpha: f64) -> usize {
    if p <= 0.0 {
        return 0;
    }
    let (ln_p, ln_q) = (p.ln(), (1.0 - p).ln());
    let mut ln_pmf = n as f64 * ln_q;
    let mut cdf = 0.0;
    for k in 0..n {
        cdf += ln_pmf.exp();
        if 1.0 - cdf <= alpha {
            return k;
        }
        ln_pmf += ((n - k) as f64 / (k + 1) as f64).ln() + ln_p - ln_q;
    }
    n
}
