//! The reflections applied four columns at a time give each column what one reflection alone
//! gives it, to the last bit; the blocked QR reproduces its matrix.

use super::householder::{qr, reflect, reflect_columns};

/// A column-major `m x n` matrix of mixed sizes and signs.
fn sample(m: usize, n: usize) -> Vec<f64> {
    (0..m * n)
        .map(|i| (0.3 + 0.71 * i as f64).sin() * 10f64.powi((i % 5) as i32 - 2))
        .collect()
}

#[test]
fn reflecting_columns_together_equals_reflecting_each_alone_to_the_last_bit() {
    let m = 70;
    for columns in 0..11 {
        for from in [0, 1, 33, 68] {
            let tail: Vec<f64> = sample(m - from - 1, 1);
            let tau = 1.37;
            let mut together = sample(m, columns);
            let mut alone = together.clone();
            reflect_columns(&tail, tau, &mut together, m, from);
            for c in alone.chunks_exact_mut(m) {
                reflect(&tail, tau, &mut c[from..]);
            }
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
            assert_eq!(
                bits(&together),
                bits(&alone),
                "{columns} columns from {from}"
            );
        }
    }
}

/// `Q R` of [`qr`]'s output: the reflections applied in reverse to `R`'s columns.
fn q_times_r(a: &[f64], taus: &[f64], m: usize, n: usize) -> Vec<f64> {
    let mut out = vec![0.0; m * n];
    for c in 0..n {
        let col = &mut out[c * m..(c + 1) * m];
        for r in 0..=c.min(m - 1) {
            col[r] = a[c * m + r];
        }
        for k in (0..taus.len()).rev() {
            reflect(&a[k * m + k + 1..(k + 1) * m], taus[k], &mut col[k..]);
        }
    }
    out
}

#[test]
fn blocked_qr_reproduces_its_matrix_across_several_blocks() {
    // 70 reflections: two whole blocks of 32 and part of a third, trailing columns in groups of
    // four and a remainder.
    let (m, n) = (90, 75);
    let a = sample(m, n);
    let mut f = a.clone();
    let taus = qr(&mut f, m, 70);
    let back = q_times_r(&f, &taus, m, 70);
    let largest = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for (x, y) in back.iter().zip(&a[..70 * m]) {
        assert!((x - y).abs() < 1e-12 * largest, "{x} against {y}");
    }
}
