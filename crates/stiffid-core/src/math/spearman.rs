//! Spearman's rank correlation (ties get mean ranks).

/// The ranks (1-based, ascending: 1 the smallest value) of a sample, ties given the mean of the
/// ranks they span.
pub fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut k = i;
        while k + 1 < order.len() && v[order[k + 1]] == v[order[i]] {
            k += 1;
        }
        for &o in &order[i..=k] {
            r[o] = 0.5 * (i + k) as f64 + 1.0;
        }
        i = k + 1;
    }
    r
}

/// Spearman's rank correlation of two equally long samples: the Pearson correlation of their
/// ranks, ties given mean ranks. In [-1, 1]; `None` for fewer than 3 values, samples of different
/// lengths or a constant sample.
///
/// # Examples
/// ```
/// let rho = stiffid_core::math::spearman(&[1.0, 2.0, 3.0], &[30.0, 20.0, 10.0]);
/// assert_eq!(rho, Some(-1.0));
/// ```
pub fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() < 3 || x.len() != y.len() {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let mean = (x.len() as f64 + 1.0) / 2.0;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mean) * (b - mean);
        sxx += (a - mean).powi(2);
        syy += (b - mean).powi(2);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}
