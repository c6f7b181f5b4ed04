//! A global search of a box for the least value of a function that may be undefined (an
//! infeasible point): a grid over the box, seeded random samples, then a compass search (a
//! pattern search along each coordinate, its steps halved when no neighbour improves; Kolda,
//! Lewis and Torczon, "Optimization by direct search", SIAM Review 45(3), 2003) from the best
//! distinct points found. Every batch of points is evaluated in parallel and reduced in a fixed
//! order, so the result does not depend on the number of threads.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

/// The box searched and how finely.
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
    /// Each coordinate's lower end.
    pub lower: Vec<f64>,
    /// Each coordinate's upper end (`>= lower`).
    pub upper: Vec<f64>,
    /// The compass search stops when every step is below this, per coordinate.
    pub tolerance: Vec<f64>,
    /// The first `gridded` coordinates get a grid of `grid` values each (the others sit at the
    /// middle of their range); the samples spread over every coordinate.
    pub gridded: usize,
}

/// How the search spends its evaluations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Effort {
    /// Grid values per gridded coordinate, >= 2.
    pub grid: usize,
    /// Seeded uniform random points over the box.
    pub samples: usize,
    /// Compass searches, from the best distinct points of the grid and the samples.
    pub starts: usize,
    /// The seed of the samples.
    pub seed: u64,
}

/// The least value found.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    /// Where.
    pub x: Vec<f64>,
    /// The value there.
    pub value: f64,
}

/// The compass search's moves at most, per start.
const MAX_MOVES: usize = 400;

/// The least value of `f` over `space` (module docs), `None` where `f` is undefined; and the
/// number of evaluations. `None` when no point evaluated is defined.
pub fn minimise<F>(space: &Space, effort: &Effort, f: F) -> (Option<Found>, usize)
where
    F: Fn(&[f64]) -> Option<f64> + Sync,
{
    let first = first_points(space, effort);
    let values: Vec<Option<f64>> = first.par_iter().map(|x| f(x)).collect();
    let mut evaluations = first.len();
    let mut ranked: Vec<(f64, usize)> = (values.iter().enumerate())
        .filter_map(|(i, v)| v.map(|v| (v, i)))
        .collect();
    ranked.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let steps = first_steps(space, effort);
    let mut starts: Vec<Found> = Vec::new();
    for (v, i) in ranked {
        if starts.len() == effort.starts {
            break;
        }
        let far = |s: &Found| (0..steps.len()).any(|k| (s.x[k] - first[i][k]).abs() > steps[k]);
        if starts.iter().all(far) {
            starts.push(Found {
                x: first[i].clone(),
                value: v,
            });
        }
    }
    let searched: Vec<(Found, usize)> = starts
        .into_par_iter()
        .map(|s| compass(space, s, steps.clone(), &f))
        .collect();
    let mut best: Option<Found> = None;
    for (found, n) in searched {
        evaluations += n;
        if best.as_ref().is_none_or(|b| found.value < b.value) {
            best = Some(found);
        }
    }
    (best, evaluations)
}

/// The grid (every combination of the gridded coordinates' values) and the seeded samples.
pub(crate) fn first_points(space: &Space, effort: &Effort) -> Vec<Vec<f64>> {
    let n = space.lower.len();
    let middle: Vec<f64> = (0..n)
        .map(|k| (space.lower[k] + space.upper[k]) / 2.0)
        .collect();
    let value = |k: usize, g: usize| {
        let t = g as f64 / (effort.grid - 1) as f64;
        space.lower[k] + t * (space.upper[k] - space.lower[k])
    };
    let mut points = vec![middle];
    for k in 0..space.gridded {
        points = points
            .iter()
            .flat_map(|p| {
                (0..effort.grid).map(move |g| {
                    let mut p = p.clone();
                    p[k] = value(k, g);
                    p
                })
            })
            .collect();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(effort.seed);
    for _ in 0..effort.samples {
        let p = (0..n)
            .map(|k| space.lower[k] + rng.random::<f64>() * (space.upper[k] - space.lower[k]))
            .collect();
        points.push(p);
    }
    points
}

/// The compass search's first steps: half the grid's spacing on the gridded coordinates, a
/// quarter of the range on the others.
fn first_steps(space: &Space, effort: &Effort) -> Vec<f64> {
    (0..space.lower.len())
        .map(|k| {
            let range = space.upper[k] - space.lower[k];
            match k < space.gridded {
                true => range / (effort.grid - 1) as f64 / 2.0,
                false => range / 4.0,
            }
        })
        .collect()
}

/// The compass search from `start`: each move to the best of the 2n neighbours one step away
/// along a coordinate (within the box) that lowers the value; no such neighbour halves every
/// step; stops when every step is below its tolerance. Returns the point and its evaluations.
fn compass<F>(space: &Space, start: Found, mut steps: Vec<f64>, f: &F) -> (Found, usize)
where
    F: Fn(&[f64]) -> Option<f64> + Sync,
{
    let n = steps.len();
    let (mut at, mut evaluations) = (start, 0);
    for _ in 0..MAX_MOVES {
        if (0..n).all(|k| steps[k] < space.tolerance[k]) {
            break;
        }
        let neighbours: Vec<Vec<f64>> = (0..2 * n)
            .filter(|m| steps[m / 2] >= space.tolerance[m / 2])
            .map(|m| {
                let (k, sign) = (m / 2, if m % 2 == 0 { -1.0 } else { 1.0 });
                let mut x = at.x.clone();
                x[k] = (x[k] + sign * steps[k]).clamp(space.lower[k], space.upper[k]);
                x
            })
            .filter(|x| *x != at.x)
            .collect();
        let values: Vec<Option<f64>> = neighbours.par_iter().map(|x| f(x)).collect();
        evaluations += neighbours.len();
        let best = (values.iter().enumerate())
            .filter_map(|(i, v)| v.map(|v| (v, i)))
            .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        match best {
            Some((v, i)) if v < at.value => {
                at = Found {
                    x: neighbours[i].clone(),
                    value: v,
                }
            }
            _ => steps.iter_mut().for_each(|s| *s /= 2.0),
        }
    }
    (at, evaluations)
}
