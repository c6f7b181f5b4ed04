//! The bidiagonalisation keeps its matrix's singular values.

use super::reflections::Bidiagonal;

/// A column-major `m x n` matrix of mixed sizes and signs.
fn sample(m: usize, n: usize) -> Vec<f64> {
    (0..m * n)
        .map(|i| (0.3 + 0.71 * i as f64).sin() * 10f64.powi((i % 5) as i32 - 2))
        .collect()
}

#[test]
fn bidiagonalisation_keeps_the_singular_values() {
    let (m, n) = (40, 23);
    let a = sample(m, n);
    let bi = Bidiagonal::new(a.clone(), m);
    let mut b = nalgebra::DMatrix::zeros(n, n);
    for i in 0..n {
        b[(i, i)] = bi.diagonal[i];
        if i + 1 < n {
            b[(i, i + 1)] = bi.upper[i];
        }
    }
    let singular = |x: nalgebra::DMatrix<f64>| {
        let mut s: Vec<f64> = x.singular_values().iter().copied().collect();
        s.sort_by(f64::total_cmp);
        s
    };
    let from_a = singular(nalgebra::DMatrix::from_column_slice(m, n, &a));
    for (x, y) in singular(b).iter().zip(&from_a) {
        assert!((x - y).abs() < 1e-12 * from_a[n - 1], "{x} against {y}");
    }
}
