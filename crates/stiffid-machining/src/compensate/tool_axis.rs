//! The free tool axis: the stiffness-optimal rotation about tool z along the path by dynamic
//! programming (module docs of [`super`], "The free tool axis").

use super::feasible::Checks;
use super::lead_tilt::{lean, Lean, Leaning};
use super::{Aggregate, FreeRange, Model, Removed, TIE_BREAK};
use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use rayon::prelude::*;
use std::cell::Cell;
use stiffid_core::observation::dynamics::tcp_surge;
use stiffid_core::robot::dynamics::MassModel;
use stiffid_core::robot::external::ExternalValues;
use stiffid_core::robot::ik::{self, tool_pose};
use stiffid_core::robot::kinematics::Frames;

/// What a point costs at an angle ([`super::Objective`]).
pub(super) enum Cost<'a> {
    /// The TCP translation deflection under the point's wrench, m.
    Deflection,
    /// The error bound under the point's wrench ([`super::Budget`], without the residual the
    /// Newton steps leave, at most 0.1 um), m.
    Bound,
    /// At a drilling exit the surge speed of its thrust (m/s), elsewhere nothing.
    Surge {
        /// The arm's mass model.
        masses: Box<MassModel>,
        /// Each point's thrust (N, base frame) at a drilling exit, `None` elsewhere.
        thrusts: &'a [Option<Vector3<f64>>],
    },
}

impl Cost<'_> {
    /// The cost of point `i` in the posture `frames` under `wrench` (base frame); `None` where
    /// it cannot be computed (a surge at a singular posture).
    fn of(&self, model: &Model, i: usize, frames: &Frames, wrench: &Vector6<f64>) -> Option<f64> {
        match self {
            Cost::Deflection => Some(model.deflection(frames, wrench).0.fixed_rows::<3>(0).norm()),
            Cost::Bound => Some(
                model
                    .budget(&model.tcp_deflection(frames, wrench), 0.0)
                    .bound,
            ),
            Cost::Surge { masses, thrusts } => match &thrusts[i] {
                None => Some(0.0),
                Some(force) => {
                    tcp_surge(masses, model.arm, frames, model.compliance, force).map(|s| s.speed)
                }
            },
        }
    }

    /// The scale of the tie-breaking cost of each point from the costs `own` at the path's
    /// angle: the point's own for the deflection, the largest for the surge (a point that is no
    /// exit costs nothing but still keeps the path smooth).
    pub(super) fn scales(&self, own: &[f64]) -> Vec<f64> {
        match self {
            Cost::Deflection | Cost::Bound => own.to_vec(),
            Cost::Surge { .. } => {
                let largest = own.iter().copied().fold(0.0, f64::max);
                vec![if largest > 0.0 { largest } else { 1.0 }; own.len()]
            }
        }
    }
}

/// The grid's axis of the rotation of `free` over its `angles` ([`FreeRange::angles`]).
pub(super) fn rotation_axis<'a>(free: &FreeRange, angles: &'a [f64]) -> Axis<'a> {
    Axis {
        values: angles,
        reach: free.cells().1,
        range: free.range,
        max_step: free.step,
        zero: angles.len() / 2,
    }
}

/// The grid's lead and tilt axes of `leaning` (none without a free lean).
pub(super) fn lean_axes(leaning: &Leaning) -> Vec<Axis<'_>> {
    let offsets = leaning.offsets();
    match offsets.last() {
        None => Vec::new(),
        Some(&range) => (0..2)
            .map(|_| Axis {
                values: offsets,
                reach: 1,
                range: range.max(leaning.step()),
                max_step: leaning.step(),
                zero: offsets.len() / 2,
            })
            .collect(),
    }
}

/// The state of every point on the path of least value over `columns` (one per state of
/// `grid`, with each point's external values `at` that state in `external`): a point takes a
/// state only where its cost is no larger than at the path's own and its moved posture passes
/// `checks` (the path's own posture is kept as it is), and moves from one point's state to the
/// next's only within the axes' speed limits of `checks` ([`super::Feasible::move_times`]; the
/// path's own moves always); with each point's states the checks removed and moves refused.
pub(super) fn choose(
    (columns, external): (&[Column], &[&[ExternalValues]]),
    grid: &Grid,
    (cost, checks): (&Cost, &Checks),
    aggregate: Aggregate,
) -> (Vec<usize>, Vec<Removed>) {
    let zero = grid.zero();
    let own: Vec<f64> = (columns[zero].iter())
        .map(|c| c.as_ref().map_or(0.0, |z| z.1))
        .collect();
    let (costs, removed): (Vec<Vec<Option<f64>>>, Vec<Removed>) = (0..own.len())
        .into_par_iter()
        .map(|i| {
            let mut removed = Removed::default();
            let own_q = columns[zero][i].as_ref().map(|z| &z.0);
            let touching = checks.touching(own_q, &external[zero][i]);
            let costs = (columns.iter().enumerate())
                .map(|(g, c)| {
                    let (q, d) = c[i].as_ref().filter(|z| z.1 <= own[i])?;
                    if g == zero {
                        return Some(*d);
                    }
                    match checks.fails(q, &external[g][i], &touching) {
                        Some(r) => {
                            removed += r;
                            None
                        }
                        None => Some(*d),
                    }
                })
                .collect();
            (costs, removed)
        })
        .unzip();
    let refused: Vec<Cell<usize>> = (0..own.len()).map(|_| Cell::new(0)).collect();
    let allowed = |i: usize, a: usize, g: usize| {
        let Some(pace) = &checks.pace else {
            return true;
        };
        let (Some(from), Some(to)) = (&columns[a][i - 1], &columns[g][i]) else {
            return true;
        };
        let ok = pace.allows(i, (&from.0, &external[a][i - 1]), (&to.0, &external[g][i]));
        if !ok {
            refused[i].set(refused[i].get() + 1);
        }
        ok
    };
    let chosen = shortest(&costs, grid, &cost.scales(&own), aggregate, &allowed);
    let mut removed = removed;
    for (r, n) in removed.iter_mut().zip(&refused) {
        r.speed = n.get();
    }
    (chosen, removed)
}

/// One axis of the grid of the free variables (the tool rotation, the track station).
pub(crate) struct Axis<'a> {
    /// The values (offsets from the path's own), ascending, rad or m.
    pub values: &'a [f64],
    /// The most cells one step between points may move.
    pub reach: usize,
    /// The range of the values, rad or m.
    pub range: f64,
    /// The largest step between points, rad or m.
    pub max_step: f64,
    /// The index of the path's own value (0).
    pub zero: usize,
}

/// The grid of the free variables: its states are the combinations of the axes' values, the
/// last axis' index running fastest.
pub(crate) struct Grid<'a> {
    /// The axes, at least one.
    pub axes: Vec<Axis<'a>>,
}

impl Grid<'_> {
    /// The number of states.
    pub(crate) fn states(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// The index on each axis of state `s`.
    pub(crate) fn indices(&self, mut s: usize) -> Vec<usize> {
        let mut out = vec![0; self.axes.len()];
        for (k, a) in self.axes.iter().enumerate().rev() {
            out[k] = s % a.values.len();
            s /= a.values.len();
        }
        out
    }

    /// The state of the path's own values.
    pub(crate) fn zero(&self) -> usize {
        (self.axes.iter()).fold(0, |s, a| s * a.values.len() + a.zero)
    }

    /// The tie-breaking distance of state `s` from the path's own values: per axis the value
    /// over its range, summed.
    fn away(&self, s: usize) -> f64 {
        let at = self.indices(s);
        (self.axes.iter().zip(&at))
            .map(|(a, &g)| a.values[g].abs() / a.range)
            .sum()
    }

    /// Every state's predecessors (the states within each axis' reach) with the tie-breaking
    /// cost of the step: per axis the change over its largest step, summed.
    fn steps(&self) -> Vec<Vec<(usize, f64)>> {
        (0..self.states())
            .map(|s| {
                let at = self.indices(s);
                let mut out = vec![(0usize, 0.0)];
                for (a, &g) in self.axes.iter().zip(&at) {
                    let lo = g.saturating_sub(a.reach);
                    let hi = (g + a.reach).min(a.values.len() - 1);
                    out = (out.iter())
                        .flat_map(|&(b, c)| {
                            (lo..=hi).map(move |h| {
                                let d = (a.values[g] - a.values[h]).abs() / a.max_step;
                                (b * a.values.len() + h, c + d)
                            })
                        })
                        .collect();
                }
                out
            })
            .collect()
    }
}

/// The value of a path so far: the aggregate of the costs (with [`Aggregate::Sum`], the
/// tie-breaking costs included) and, for [`Aggregate::Max`], the sum with them as the tie-break.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Value {
    /// What is minimised.
    pub primary: f64,
    /// What breaks its ties.
    pub secondary: f64,
}

impl Value {
    pub(super) const INFINITE: Value = Value {
        primary: f64::INFINITY,
        secondary: f64::INFINITY,
    };

    /// The value of the empty path: nothing summed, the worst of nothing.
    pub(super) fn start(aggregate: Aggregate) -> Value {
        Value {
            primary: match aggregate {
                Aggregate::Sum => 0.0,
                Aggregate::Max => f64::NEG_INFINITY,
            },
            secondary: 0.0,
        }
    }

    /// The value of the path continued by a point of cost `d` with the tie-breaking cost `tie`.
    pub(super) fn then(self, d: f64, tie: f64, aggregate: Aggregate) -> Value {
        match aggregate {
            Aggregate::Sum => Value {
                primary: self.primary + d + tie,
                secondary: 0.0,
            },
            Aggregate::Max => Value {
                primary: self.primary.max(d),
                secondary: self.secondary + d + tie,
            },
        }
    }

    pub(super) fn less(&self, other: &Value) -> bool {
        match self.primary.total_cmp(&other.primary) {
            std::cmp::Ordering::Equal => self.secondary < other.secondary,
            o => o.is_lt(),
        }
    }
}

/// The dynamic programming of the free tool axis: `costs[i][g]` the cost of point `i` at angle
/// `g` (`None`: not feasible), `scales[i]` its tie-breaking scale, `allowed(i, a, g)` whether
/// the move from state `a` at point `i - 1` to state `g` at point `i` may be taken (the axes'
/// speed limits; the path's own move, `grid.zero` to `grid.zero`, always is); returns the
/// angle index of each point on the path of least value (module docs of [`super`]),
/// `grid.zero` everywhere when no path is feasible.
pub(crate) fn shortest(
    costs: &[Vec<Option<f64>>],
    grid: &Grid,
    scales: &[f64],
    aggregate: Aggregate,
    allowed: &dyn Fn(usize, usize, usize) -> bool,
) -> Vec<usize> {
    let n = costs.len();
    let (g_count, zero) = (grid.states(), grid.zero());
    let steps = grid.steps();
    let away: Vec<f64> = (0..g_count).map(|s| grid.away(s)).collect();
    // value[i][g]: the least value of the paths up to point i ending at state g.
    let mut value = vec![vec![Value::INFINITE; g_count]; n];
    let mut from = vec![vec![0usize; g_count]; n];
    let add = |before: Value, d: f64, tie: f64| before.then(d, tie, aggregate);
    let start = Value::start(aggregate);
    for i in 0..n {
        let w = TIE_BREAK * scales[i];
        for g in 0..g_count {
            let Some(d) = costs[i][g] else { continue };
            let tie = w * away[g];
            if i == 0 {
                value[0][g] = add(start, d, tie);
                continue;
            }
            let mut best: Option<(usize, Value)> = None;
            for &(a, step) in &steps[g] {
                if value[i - 1][a].primary == f64::INFINITY {
                    continue;
                }
                let own = a == zero && g == zero;
                if !own && !allowed(i, a, g) {
                    continue;
                }
                let v = add(value[i - 1][a], d, tie + w * step);
                if best.is_none_or(|(_, b)| v.less(&b)) {
                    best = Some((a, v));
                }
            }
            if let Some((a, v)) = best {
                value[i][g] = v;
                from[i][g] = a;
            }
        }
    }
    let last = (0..g_count).fold(None, |best: Option<usize>, g| match best {
        Some(b) if !value[n - 1][g].less(&value[n - 1][b]) => Some(b),
        _ if value[n - 1][g].primary == f64::INFINITY => best,
        _ => Some(g),
    });
    let Some(mut g) = last else {
        return vec![zero; n];
    };
    let mut chosen = vec![zero; n];
    for i in (0..n).rev() {
        chosen[i] = g;
        g = from[i][g];
    }
    chosen
}

/// One state's posture and cost at every path point; `None` where inverse kinematics fails
/// or the cost cannot be computed.
pub(crate) type Column = Vec<Option<(Vector6<f64>, f64)>>;

/// How a state of the grid moves each point's pose from the path's own: turned by `phi` about
/// tool z, leaned by `lean` ([`super::lean`]), then, on a moved track station, taken by each
/// point's `shift` (the arm's frame at the path's station seen from the arm's frame at the
/// state's, [`super::station`]); a refined state ([`super::refine`]) adds each point's `line`
/// to the rotation and the lean.
#[derive(Clone, Copy)]
pub(super) struct Move<'a> {
    /// The rotation about tool z, rad.
    pub phi: f64,
    /// Each point's change of the arm's frame; `None` at the path's own station.
    pub shift: Option<&'a [Isometry3<f64>]>,
    /// The lean; `None` without a free lead and tilt.
    pub lean: Option<Lean<'a>>,
    /// Each point's `[rotation, lead, tilt]` (rad) added to `phi` and the lean's: the line a
    /// refined band lies around; `None`: none.
    pub line: Option<&'a [[f64; 3]]>,
}

impl Move<'_> {
    /// Whether this is the path's own pose.
    fn own(&self) -> bool {
        let still = self.shift.is_none() && self.line.is_none();
        self.phi == 0.0 && still && self.lean.is_none_or(|l| l.zero())
    }

    /// The rotation, lead and tilt at point `i`, rad.
    fn at(&self, i: usize) -> [f64; 3] {
        let [phi, lead, tilt] = self.line.map_or([0.0; 3], |l| l[i]);
        let (l, t) = self.lean.map_or((0.0, 0.0), |l| (l.lead, l.tilt));
        [self.phi + phi, l + lead, t + tilt]
    }
}

/// The postures of the path moved by `m` ([`Move`]), continued along the path, and their cost
/// under `wrenches` (the arm's frame of the state); `None` where inverse kinematics fails or
/// the cost cannot be computed (at the path's own pose such a cost is 0: no other state is then
/// taken there).
pub(super) fn column(
    model: &Model,
    nominal: &[Vector6<f64>],
    wrenches: &[Vector6<f64>],
    (m, cost): (Move, &Cost),
    ik_options: &ik::Options,
) -> Column {
    let arm = model.arm;
    let tcp = &arm.tool().tcp;
    let options = ik::Options {
        restarts: 0,
        ..*ik_options
    };
    let mut previous: Option<Vector6<f64>> = None;
    nominal
        .iter()
        .zip(wrenches)
        .enumerate()
        .map(|(i, (q, w))| {
            let [phi, lead, tilt] = m.at(i);
            let inside = m.lean.is_none_or(|l| l.inside(i, lead, tilt));
            let q = match (m.own(), inside) {
                (true, _) => Some(*q),
                (false, false) => None,
                (false, true) => {
                    let mut target = tool_pose(&arm.robot().frames(q), tcp);
                    target.rotation *= UnitQuaternion::from_axis_angle(&Vector3::z_axis(), phi);
                    if let Some(l) = &m.lean {
                        target.rotation = lean(&l.frames[i], lead, tilt) * target.rotation;
                    }
                    if let Some(shift) = m.shift {
                        target = shift[i] * target;
                    }
                    let start = previous.unwrap_or(*q);
                    ik::solve(arm.robot(), tcp, &target, &start, &options)
                        .or_else(|_| ik::solve(arm.robot(), tcp, &target, q, &options))
                        .ok()
                        .map(|s| s.q)
                }
            };
            previous = q;
            let q = q?;
            match cost.of(model, i, &arm.robot().frames(&q), w) {
                Some(c) => Some((q, c)),
                None if m.own() => Some((q, 0.0)),
                None => None,
            }
        })
        .collect()
}
