//! The dynamic programming over the free angles (`crate::compensate::tool_axis`).

use crate::compensate::tool_axis::*;
use crate::compensate::Aggregate;

/// Every path of angle indices over `n` points on `g` angles whose consecutive indices
/// differ by at most `reach` and whose moves `allowed` takes (the own angle `zero` kept
/// always allowed), by enumeration: the least aggregate of the costs.
fn exhaustive(
    costs: &[Vec<Option<f64>>],
    (reach, zero): (usize, usize),
    aggregate: Aggregate,
    allowed: &dyn Fn(usize, usize, usize) -> bool,
) -> f64 {
    let (n, g) = (costs.len(), costs[0].len());
    let mut best = f64::INFINITY;
    for code in 0..g.pow(n as u32) {
        let path: Vec<usize> = (0..n).map(|i| code / g.pow(i as u32) % g).collect();
        if path.windows(2).any(|w| w[0].abs_diff(w[1]) > reach) {
            continue;
        }
        let refused = (1..n).any(|i| {
            let own = path[i - 1] == zero && path[i] == zero;
            !own && !allowed(i, path[i - 1], path[i])
        });
        if refused {
            continue;
        }
        let values: Option<Vec<f64>> = (0..n).map(|i| costs[i][path[i]]).collect();
        let Some(values) = values else { continue };
        let value = match aggregate {
            Aggregate::Sum => values.iter().sum(),
            Aggregate::Max => values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        };
        best = best.min(value);
    }
    best
}

#[test]
fn the_dynamic_programming_finds_the_exhaustive_optimum_with_refused_moves() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let angles = [-0.2, -0.1, 0.0, 0.1, 0.2];
    let grid = Grid {
        axes: vec![Axis {
            values: &angles,
            reach: 1,
            range: 0.2,
            max_step: 0.1,
            zero: 2,
        }],
    };
    for trial in 0..40 {
        let n = 6;
        // Costs in [1, 2) mm with some infeasible cells, the path's own angle always feasible.
        let costs: Vec<Vec<Option<f64>>> = (0..n)
            .map(|_| {
                (0..5)
                    .map(|g| {
                        (g == 2 || rng.random::<f64>() > 0.2).then(|| 1.0 + rng.random::<f64>())
                    })
                    .collect()
            })
            .collect();
        let scales = vec![1.0; n];
        // Every third trial refuses a random third of the moves (the speed limits).
        let mask: Vec<bool> = (0..n * 25).map(|_| rng.random::<f64>() > 0.33).collect();
        let masked = trial % 3 == 0;
        let allowed = |i: usize, a: usize, g: usize| !masked || mask[i * 25 + a * 5 + g];
        for aggregate in [Aggregate::Sum, Aggregate::Max] {
            let chosen = shortest(&costs, &grid, &scales, aggregate, &allowed);
            assert!(chosen.windows(2).all(|w| w[0].abs_diff(w[1]) <= 1));
            let taken = (1..n).all(|i| {
                let own = chosen[i - 1] == 2 && chosen[i] == 2;
                own || allowed(i, chosen[i - 1], chosen[i])
            });
            assert!(taken, "trial {trial}: a refused move taken");
            let values: Vec<f64> = (0..n).map(|i| costs[i][chosen[i]].unwrap()).collect();
            let value = match aggregate {
                Aggregate::Sum => values.iter().sum(),
                Aggregate::Max => values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            };
            let best = exhaustive(&costs, (1, 2), aggregate, &allowed);
            // Equal up to the tie-breaking cost (1e-6 of a cost per point and step).
            assert!(
                (value - best).abs() <= 1e-5,
                "trial {trial} {aggregate:?}: {value} against {best}"
            );
        }
    }
}
