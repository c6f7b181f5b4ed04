//! The refined band's dynamic programming (`crate::compensate::refine`).

use crate::compensate::refine::*;
use crate::compensate::tool_axis::Axis;
use crate::compensate::tool_axis::{Column, Grid};
use crate::compensate::Aggregate;
use nalgebra::Vector6;
use rand::{Rng, SeedableRng};
use stiffid_core::robot::external::ExternalValues;

/// The aggregate of `costs`.
fn total(costs: &[f64], aggregate: Aggregate) -> f64 {
    match aggregate {
        Aggregate::Sum => costs.iter().sum(),
        Aggregate::Max => costs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    }
}

/// Band state `s`'s values at point `i` of `line` with the halved steps `half` (rad), the
/// offsets `-2..=2` per axis, the last axis fastest.
fn value(line: &[Vec<f64>], half: &[f64], i: usize, mut s: usize) -> Vec<f64> {
    let mut out = line[i].clone();
    for k in (0..out.len()).rev() {
        out[k] += ((s % 5) as f64 - 2.0) * half[k];
        s /= 5;
    }
    out
}

/// The least aggregate over every choice of one band state per point whose values change
/// by at most `max_step` per axis between points, by enumeration: a depth-first walk over every
/// such choice (a choice is dropped at the first point it cannot take, which no cost can repair).
fn exhaustive(
    (line, half, max_step): (&[Vec<f64>], &[f64], &[f64]),
    cells: &[Column],
    aggregate: Aggregate,
) -> f64 {
    let values: Vec<Vec<Vec<f64>>> = (0..line.len())
        .map(|i| (0..cells.len()).map(|s| value(line, half, i, s)).collect())
        .collect();
    let mut best = f64::INFINITY;
    walk(
        (&values, max_step, cells, aggregate),
        None,
        &mut Vec::new(),
        &mut best,
    );
    best
}

/// Each point's band states' values, the steps allowed, the cells and the aggregate.
type Enumeration<'a> = (&'a [Vec<Vec<f64>>], &'a [f64], &'a [Column], Aggregate);

/// Extends the choice whose costs are `costs` (its last state `last`) by every state the next
/// point can take, lowering `best` at each complete choice.
fn walk(
    enumeration @ (values, max_step, cells, aggregate): Enumeration,
    last: Option<usize>,
    costs: &mut Vec<f64>,
    best: &mut f64,
) {
    let i = costs.len();
    if i == values.len() {
        *best = best.min(total(costs, aggregate));
        return;
    }
    for (s, column) in cells.iter().enumerate() {
        let fast = last.is_some_and(|p| {
            (values[i - 1][p].iter().zip(&values[i][s]).zip(max_step))
                .any(|((a, b), m)| (a - b).abs() > m * (1.0 + 1e-9))
        });
        if let (false, Some(cell)) = (fast, &column[i]) {
            costs.push(cell.1);
            walk(enumeration, Some(s), costs, best);
            costs.pop();
        }
    }
}

#[test]
fn the_band_dynamic_programming_finds_the_exhaustive_optimum_and_never_rises() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    const A: [f64; 5] = [-0.2, -0.1, 0.0, 0.1, 0.2];
    const B: [f64; 5] = [-0.1, -0.05, 0.0, 0.05, 0.1];
    let axis = |values: &'static [f64], reach: usize, max_step: f64| Axis {
        values,
        reach,
        range: 0.2,
        max_step,
        zero: 2,
    };
    // One axis of reach 1 over 7 points; two axes (the second of reach 2) over 4 points.
    let cases = [
        (vec![axis(&A, 1, 0.1)], 7),
        (vec![axis(&A, 1, 0.1), axis(&B, 2, 0.1)], 4),
    ];
    for (axes, n) in cases {
        let grid = Grid { axes };
        let max_step: Vec<f64> = grid.axes.iter().map(|a| a.max_step).collect();
        let half: Vec<f64> = (grid.axes.iter())
            .map(|a| a.max_step / a.reach as f64 / 2.0)
            .collect();
        for trial in 0..12 {
            // A line on the grid moving by at most each axis' reach per point.
            let mut at: Vec<usize> = vec![2; grid.axes.len()];
            let values: Vec<Vec<f64>> = (0..n)
                .map(|_| {
                    (grid.axes.iter().zip(&mut at))
                        .map(|(x, g)| {
                            let step =
                                rng.random_range(0..=2 * x.reach) as isize - x.reach as isize;
                            *g = (*g as isize + step).clamp(0, 4) as usize;
                            x.values[*g]
                        })
                        .collect()
                })
                .collect();
            let line = Line {
                values: values.clone(),
                cells: vec![Some((Vector6::zeros(), 1.5)); n],
                external: vec![ExternalValues::default(); n],
            };
            let band = Band::new(&grid, &line, 1);
            // Costs in [1, 2) with some cells missing, the line's own always there.
            let cells: Vec<Column> = (0..band.states())
                .map(|s| {
                    (0..n)
                        .map(|i| match s == band.centre() {
                            true => line.cells[i],
                            false => (rng.random::<f64>() > 0.2)
                                .then(|| (Vector6::zeros(), 1.0 + rng.random::<f64>())),
                        })
                        .collect()
                })
                .collect();
            for aggregate in [Aggregate::Sum, Aggregate::Max] {
                let external = vec![vec![ExternalValues::default(); n]; band.states()];
                let chosen = band.shortest((&cells, &external), &vec![1.0; n], aggregate, None);
                let costs: Vec<f64> = chosen.cells.iter().map(|c| c.as_ref().unwrap().1).collect();
                let found = total(&costs, aggregate);
                let best = exhaustive((&values, &half, &max_step), &cells, aggregate);
                // Equal up to the tie-breaking cost (1e-6 of a cost per point and step).
                assert!(
                    (found - best).abs() <= 1e-5,
                    "trial {trial} {aggregate:?}: {found} against {best}"
                );
                assert!(found <= total(&[1.5; 7][..n], aggregate) + 1e-5);
                for w in chosen.values.windows(2) {
                    for ((x, y), m) in w[0].iter().zip(&w[1]).zip(&max_step) {
                        assert!((x - y).abs() <= m * (1.0 + 1e-9), "{x} to {y}");
                    }
                }
            }
        }
    }
}
