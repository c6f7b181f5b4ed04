//! The free variables' grid refined where it matters: after the dynamic programming on the
//! grid, a band of finer steps around the line it chose, level after level (module docs of
//! [`super`], "Refining the grid").

use super::feasible::{Checks, Removed};
use super::speed::Pace;
use super::tool_axis::{Column, Cost, Grid, Value};
use super::{Aggregate, TIE_BREAK};
use rayon::prelude::*;
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::{Error, Result};

/// The most levels of refinement (`--refine`): each halves the step, so 4 levels take a 5 deg
/// grid to 0.3125 deg.
pub(crate) const MAX_LEVELS: usize = 4;
/// Each level's band: the previous level's line plus or minus this many of its cells, on every
/// axis (`4 BAND + 1` values of the halved step per axis).
pub(crate) const BAND: usize = 1;
/// The most `states^2 x points` of one level's dynamic programming (every band state's
/// predecessors at every point).
pub(crate) const MAX_TRANSITIONS: f64 = 2e9;

/// A refined band's column and each point's external values (the checks'), from each point's
/// values on every axis of the grid (offsets from the path's own, rad or m, the grid's axis
/// order).
pub(super) type Evaluate<'a> = dyn Fn(&[Vec<f64>]) -> (Column, Vec<ExternalValues>) + Sync + 'a;

/// Where a grid's values of a state are: the free external axes first, then the lead and the
/// tilt, then the rotation about tool z (the order of the callers' [`Grid`]s).
pub(super) struct Layout {
    /// The index of the lead (the tilt's follows); `None` without a free lean.
    lean: Option<usize>,
    /// Whether the rotation is free (the last value).
    rotation: bool,
}

impl Layout {
    /// The layout of `external` free external axes, `leaning`'s axes (none without a free
    /// lean) and the rotation if free.
    pub(super) fn new(
        external: usize,
        leaning: &super::lead_tilt::Leaning,
        rotation: bool,
    ) -> Self {
        Layout {
            lean: (!leaning.offsets().is_empty()).then_some(external),
            rotation,
        }
    }

    /// The rotation, the lead and the tilt of `values` (rad; 0 for an axis not free).
    pub(crate) fn turn_lean(&self, values: &[f64]) -> [f64; 3] {
        let (lead, tilt) = self.lean.map_or((0.0, 0.0), |k| (values[k], values[k + 1]));
        let phi = match self.rotation {
            true => values[values.len() - 1],
            false => 0.0,
        };
        [phi, lead, tilt]
    }
}

/// A line through the grid: each point's values on every axis (offsets from the path's own,
/// rad or m) and its cell (posture and cost).
pub(crate) struct Line {
    /// Per point, per axis of the grid, the value.
    pub values: Vec<Vec<f64>>,
    /// Per point the posture and the cost at the values.
    pub cells: Column,
    /// Per point the external axes' values at the values (SI, the cell's order; empty on a
    /// fixed base), what the axes' speed limits check.
    pub external: Vec<ExternalValues>,
}

/// Refuses more than 4 levels (`MAX_LEVELS`), and a band of more cells than 5 000 000 or more
/// transitions than 2e9 on a grid of `axes` axes over `points` points.
///
/// # Errors
/// [`Error::InvalidOption`] ([`JobOption::Refine`]) naming the levels, states and points.
pub fn check(levels: usize, axes: usize, points: usize) -> Result<()> {
    let refuse = |message: String| {
        Err(Error::InvalidOption {
            option: JobOption::Refine,
            message,
        })
    };
    if levels > MAX_LEVELS {
        return refuse(format!("{levels}: expected 0 to {MAX_LEVELS}"));
    }
    let states = ((4 * BAND + 1) as f64).powi(axes as i32);
    let (cells, transitions) = (states * points as f64, states * states * points as f64);
    if levels > 0 && (cells > super::MAX_GRID_CELLS || transitions > MAX_TRANSITIONS) {
        return refuse(format!("{levels}: {axes} free axes make {states} band states x {points} path points ({cells:.3e} cells, {transitions:.3e} transitions); at most {:.0e} cells and {MAX_TRANSITIONS:.0e} transitions (fewer free variables or a shorter path)", super::MAX_GRID_CELLS));
    }
    Ok(())
}

/// The line `chosen` (each point's state of `grid` over its `columns`) refined `levels` times:
/// at each level the states are the previous line plus `k` halved steps on every axis, `|k| <=
/// 2` [`BAND`], within each axis' range, each band's postures continued along the path by
/// `evaluate`, a cell taken where its cost is no larger than at the path's own values and its
/// posture passes `checks` (the previous line's cells and the path's own as they are; the
/// states the checks remove added to `removed`), and the same dynamic programming as
/// [`super::tool_axis::shortest`] chooses the line of least value whose every axis changes by
/// at most its `max_step` between points. The previous line is in the band, so the value
/// never rises.
pub(super) fn refine(
    grid: &Grid,
    (columns, chosen, external): (&[Column], &[usize], &[&[ExternalValues]]),
    (levels, evaluate): (usize, &Evaluate),
    (cost, checks): (&Cost, &Checks),
    aggregate: Aggregate,
    removed: &mut [Removed],
) -> Line {
    let own = &columns[grid.zero()];
    if chosen.is_empty() {
        return Line {
            values: Vec::new(),
            cells: Vec::new(),
            external: Vec::new(),
        };
    }
    let value_of = |s: usize| -> Vec<f64> {
        let at = grid.indices(s);
        (grid.axes.iter().zip(&at))
            .map(|(a, &g)| a.values[g])
            .collect()
    };
    let mut line = Line {
        values: chosen.iter().map(|&s| value_of(s)).collect(),
        cells: (chosen.iter().enumerate())
            .map(|(i, &s)| columns[s][i])
            .collect(),
        external: (chosen.iter().enumerate())
            .map(|(i, &s)| external[s][i])
            .collect(),
    };
    let own_costs: Vec<f64> = own
        .iter()
        .map(|c| c.as_ref().map_or(0.0, |z| z.1))
        .collect();
    let scales = cost.scales(&own_costs);
    let touching: Vec<Vec<usize>> = (own.iter().zip(external[grid.zero()]))
        .map(|(c, e)| checks.touching(c.as_ref().map(|z| &z.0), e))
        .collect();
    for level in 1..=levels {
        let band = Band::new(grid, &line, level);
        let with = (checks, touching.as_slice());
        let (cells, external) = band.cells((&line, own), evaluate, with, removed);
        line = band.shortest(
            (&cells, &external),
            &scales,
            aggregate,
            checks.pace.as_ref(),
        );
    }
    line
}

/// One level's band around a line: per axis its step, the most steps between points, the
/// values within the range (in steps), and the line in steps.
pub(crate) struct Band {
    /// Per axis the step, rad or m.
    step: Vec<f64>,
    /// Per axis the most steps between consecutive points.
    reach: Vec<i64>,
    /// Per axis the most steps from the path's own value.
    limit: Vec<i64>,
    /// Per axis the range, rad or m (the tie-breaking distance's scale).
    range: Vec<f64>,
    /// Per point, per axis, the line's value in steps.
    line: Vec<Vec<i64>>,
}

/// The band's half width in steps on every axis.
const WIDTH: i64 = 2 * BAND as i64;

impl Band {
    /// The band of `level` (1 first) of `grid`'s axes around `line`.
    pub(crate) fn new(grid: &Grid, line: &Line, level: usize) -> Self {
        let fine = (1u64 << level) as f64;
        let step: Vec<f64> = (grid.axes.iter())
            .map(|a| a.max_step / a.reach as f64 / fine)
            .collect();
        let to_steps = |v: &[f64]| -> Vec<i64> {
            v.iter()
                .zip(&step)
                .map(|(x, h)| (x / h).round() as i64)
                .collect()
        };
        Band {
            reach: (grid.axes.iter())
                .map(|a| a.reach as i64 * (1 << level))
                .collect(),
            limit: (grid.axes.iter().zip(&step))
                .map(|(a, h)| (a.range / h + 1e-9).floor() as i64)
                .collect(),
            range: grid.axes.iter().map(|a| a.range).collect(),
            line: line.values.iter().map(|v| to_steps(v)).collect(),
            step,
        }
    }

    /// The number of states: `(2 WIDTH + 1)^axes`.
    pub(crate) fn states(&self) -> usize {
        (2 * WIDTH as usize + 1).pow(self.step.len() as u32)
    }

    /// The state whose offsets are all 0 (the line itself).
    pub(crate) fn centre(&self) -> usize {
        self.states() / 2
    }

    /// State `s`'s offset from the line on every axis, in steps (the last axis fastest).
    fn offsets(&self, mut s: usize) -> Vec<i64> {
        let width = 2 * WIDTH as usize + 1;
        let mut out = vec![0; self.step.len()];
        for k in (0..out.len()).rev() {
            out[k] = (s % width) as i64 - WIDTH;
            s /= width;
        }
        out
    }

    /// State `s`'s values at point `i`, in steps from the path's own.
    fn at(&self, i: usize, s: usize) -> Vec<i64> {
        let u = self.offsets(s);
        self.line[i].iter().zip(&u).map(|(l, d)| l + d).collect()
    }

    /// Every state's column: the line's own cells for the centre, else `evaluate`'s along the
    /// band state's values, a cell kept where within the range, no costlier than the path's
    /// own and passing `checks` (the path's own cells where the values are the path's own).
    fn cells(
        &self,
        (line, own): (&Line, &Column),
        evaluate: &Evaluate,
        checks: (&Checks, &[Vec<usize>]),
        removed: &mut [Removed],
    ) -> (Vec<Column>, Vec<Vec<ExternalValues>>) {
        let n = line.values.len();
        let evaluated: Vec<(Column, Vec<ExternalValues>, Vec<Removed>)> = (0..self.states())
            .into_par_iter()
            .map(|s| {
                if s == self.centre() {
                    return (line.cells.clone(), line.external.clone(), Vec::new());
                }
                let steps: Vec<Vec<i64>> = (0..n).map(|i| self.at(i, s)).collect();
                let values: Vec<Vec<f64>> = (steps.iter())
                    .map(|v| {
                        v.iter()
                            .zip(&self.step)
                            .map(|(&k, h)| k as f64 * h)
                            .collect()
                    })
                    .collect();
                let (column, external) = evaluate(&values);
                let mut removed = vec![Removed::default(); n];
                let cells = (0..n)
                    .map(|i| {
                        self.cell(
                            i,
                            &steps[i],
                            (&column, own),
                            (&external, checks),
                            &mut removed[i],
                        )
                    })
                    .collect();
                (cells, external, removed)
            })
            .collect();
        (evaluated.into_iter())
            .map(|(cells, external, r)| {
                for (total, r) in removed.iter_mut().zip(r) {
                    *total += r;
                }
                (cells, external)
            })
            .unzip()
    }

    /// Point `i`'s cell at the values `steps` of a band state whose column is `column`: the
    /// path's own at its own values, none beyond the range or costlier than the path's own or
    /// failing `checks` (counted in `removed`).
    fn cell(
        &self,
        i: usize,
        steps: &[i64],
        (column, own): (&Column, &Column),
        (external, (checks, touching)): (&[ExternalValues], (&Checks, &[Vec<usize>])),
        removed: &mut Removed,
    ) -> Option<(nalgebra::Vector6<f64>, f64)> {
        if steps.iter().all(|&k| k == 0) {
            return own[i];
        }
        if steps.iter().zip(&self.limit).any(|(k, l)| k.abs() > *l) {
            return None;
        }
        let limit = own[i].as_ref().map_or(0.0, |z| z.1);
        let (q, d) = column[i].as_ref().filter(|z| z.1 <= limit)?;
        match checks.fails(q, &external[i], &touching[i]) {
            Some(r) => {
                *removed += r;
                None
            }
            None => Some((*q, *d)),
        }
    }

    /// The line of least value over `cells` (module docs of [`super`]: the costs added up by
    /// `aggregate`, the tie-breaking costs scaled by `scales`), every axis changing by at most
    /// its reach between points and, with speed limits `pace`, every move but the path's own
    /// between two points within them (as the tool axis choice's).
    pub(crate) fn shortest(
        &self,
        (cells, external): (&[Column], &[Vec<ExternalValues>]),
        scales: &[f64],
        aggregate: Aggregate,
        pace: Option<&Pace>,
    ) -> Line {
        let allowed = |i: usize, a: usize, g: usize| {
            let own = |p: usize, s: usize| self.at(p, s).iter().all(|&k| k == 0);
            let (Some(pace), Some(from), Some(to)) = (pace, cells[a][i - 1], cells[g][i]) else {
                return true;
            };
            (own(i - 1, a) && own(i, g))
                || pace.allows(i, (&from.0, &external[a][i - 1]), (&to.0, &external[g][i]))
        };
        let (n, states) = (self.line.len(), self.states());
        let mut value = vec![vec![Value::INFINITE; states]; n];
        let mut from = vec![vec![0usize; states]; n];
        for i in 0..n {
            let w = TIE_BREAK * scales[i];
            for g in 0..states {
                let Some(d) = cells[g][i].as_ref().map(|z| z.1) else {
                    continue;
                };
                let here = self.at(i, g);
                let tie = w * self.away(&here);
                if i == 0 {
                    value[0][g] = Value::start(aggregate).then(d, tie, aggregate);
                    continue;
                }
                let mut best: Option<(usize, Value)> = None;
                for (a, step) in self.before(i, &here) {
                    if value[i - 1][a].primary == f64::INFINITY || !allowed(i, a, g) {
                        continue;
                    }
                    let v = value[i - 1][a].then(d, tie + w * step, aggregate);
                    if best.is_none_or(|(_, b)| v.less(&b)) {
                        best = Some((a, v));
                    }
                }
                if let Some((a, v)) = best {
                    (value[i][g], from[i][g]) = (v, a);
                }
            }
        }
        let mut g = (0..states).fold(self.centre(), |b, g| {
            match value[n - 1][g].less(&value[n - 1][b]) {
                true => g,
                false => b,
            }
        });
        let mut chosen = vec![0; n];
        for i in (0..n).rev() {
            chosen[i] = g;
            g = from[i][g];
        }
        Line {
            values: (chosen.iter().enumerate())
                .map(|(i, &s)| {
                    let at = self.at(i, s);
                    at.iter()
                        .zip(&self.step)
                        .map(|(&k, h)| k as f64 * h)
                        .collect()
                })
                .collect(),
            cells: (chosen.iter().enumerate())
                .map(|(i, &s)| cells[s][i])
                .collect(),
            external: (chosen.iter().enumerate())
                .map(|(i, &s)| external[s][i])
                .collect(),
        }
    }

    /// The tie-breaking distance of the values `steps` from the path's own: per axis the value
    /// over its range, summed.
    fn away(&self, steps: &[i64]) -> f64 {
        (steps.iter().zip(&self.step).zip(&self.range))
            .map(|((&k, h), r)| (k as f64 * h).abs() / r)
            .sum()
    }

    /// The states at point `i - 1` within every axis' reach of the values `here` (steps) at
    /// point `i`, with the tie-breaking cost of the step: per axis the change over its largest
    /// step, summed.
    fn before(&self, i: usize, here: &[i64]) -> Vec<(usize, f64)> {
        let mut out = vec![(0usize, 0.0)];
        for (k, &h) in here.iter().enumerate() {
            let previous = self.line[i - 1][k];
            let lo = (h - self.reach[k] - previous).max(-WIDTH);
            let hi = (h + self.reach[k] - previous).min(WIDTH);
            out = (out.iter())
                .flat_map(|&(b, c)| {
                    (lo..=hi).map(move |u| {
                        let d = (h - previous - u).abs() as f64 / self.reach[k] as f64;
                        (b * (2 * WIDTH as usize + 1) + (u + WIDTH) as usize, c + d)
                    })
                })
                .collect();
        }
        out
    }
}
