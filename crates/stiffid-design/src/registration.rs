//! Registration postures: the `n` postures, inside the setup's bounds and its cell, whose
//! measuring points determine the tracker's transform best.
//!
//! **Criterion.** The registration's covariance per unit noise is `(J^T J)^-1` (module
//! [`stiffid_metrology::register`]; Umeyama 1991, Horn 1987), `J` stacking `[I, -[b_i]x]` for every point `b_i` (base
//! frame) read. Only its rotation block matters for identification: a displacement measured in
//! the tracker frame is turned into the base frame by the rotation alone (the translation
//! cancels in loaded minus unloaded), and a rotation error `dtheta` moves a displacement `d` by
//! `dtheta x d`. The design minimises the rotation's standard deviation per unit noise
//! `sqrt(tr C_rr)` (A-optimality on the rotation, rad per m of noise), the root of the summed
//! variances of the three rotation angles. Unlike the trace or the determinant of the whole 6 x 6
//! covariance it does not mix metres with radians, and it does not depend on where the base
//! origin is: by the Schur complement, `C_rr = (sum_i (|c_i|^2 I - c_i c_i^T))^-1` with
//! `c_i = b_i - mean(b)` the centred points, the inverse of the points' inertia tensor about
//! their centroid. So the best postures spread the points far from their common centroid in every
//! direction.
//!
//! **Search.** Candidate postures are drawn uniformly in the setup's bounds (ChaCha8, stream 0 of
//! the seed) and kept when they pass the cell's checks that apply without the load: floor,
//! obstacles, self-collision, line of sight and incidence (the rope and the load's constraints do
//! not, the load is not hung while registering). The best group of `n` of them is chosen like a
//! pool's (`design::exchange`: enumeration when there are few groups, else the modified
//! Fedorov exchange from seeded groups), each posture contributing the point count, the sum and
//! the inertia about the base origin of its points, so a group's `C_rr` is one 3 x 3 Cholesky.
//! A coordinate search then moves each chosen posture's axis angles while the criterion falls
//! and the posture stays feasible, and the group's covariance is recomputed by the
//! SVD of its `J` ([`stiffid_metrology::register::unit_covariance`]). The same seed gives the same postures whatever
//! the thread count. On the guide's tracker cell, five postures: 1.50e-4 deg from 20 000
//! candidates (the default), 1.33e-4 deg from 100 000, against a median of 3.6e-4 deg for
//! random feasible groups.

use crate::{exchange, PoolMethod, PoolOptions};
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use stiffid_core::cell::{CheckKind, Checker};
use stiffid_core::common::limits;
use stiffid_core::{Error, Result, Setup};
use stiffid_metrology::register::{unit_covariance, MIN_POINTS};

/// Most candidate postures drawn ([`Options::candidates`]).
pub const MAX_CANDIDATES: usize = 100_000;

/// Most postures of a registration design.
pub const MAX_POSTURES: usize = crate::pool::MAX_GROUP;

/// Random groups of the comparison ([`Design::random_median_rotation_std`]).
pub(crate) const RANDOM_GROUPS: usize = 101;

/// Halvings of the coordinate search's step ([`polish`]).
const POLISH_HALVINGS: i32 = 8;

/// Most passes over every posture and axis at one step of the coordinate search.
const POLISH_PASSES: usize = 20;

/// The checks that need the load hung: they do not apply while registering.
pub const LOAD_CHECKS: [CheckKind; 3] = [
    CheckKind::Rope,
    CheckKind::LoadingPointHeight,
    CheckKind::AnchorBelow,
];

/// How the registration postures are searched.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Seed of the candidates, the exchange runs and the random comparison groups (default 1).
    pub seed: u64,
    /// Candidate postures drawn in the bounds before the cell's checks, 1 to [`MAX_CANDIDATES`]
    /// (default 20 000).
    pub candidates: usize,
    /// Exchange runs, 1 to [`limits::MAX_POOL_RESTARTS`] (default 8).
    pub restarts: usize,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            seed: 1,
            candidates: 20_000,
            restarts: 8,
        }
    }
}

/// The registration postures proposed and how well they determine the transform.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// The postures (axis angles, rad), in candidate order.
    pub postures: Vec<Vector6<f64>>,
    /// Covariance of `[dp (m); dtheta (rad)]` at the setup's noise (its `sigma` per coordinate
    /// of one reading, level multiple 1), base frame: `sigma^2 (J^T J)^-1` with `J` stacking
    /// `[I, -[b_i - p]x]`, `p` the tracker frame's origin (the translation of `[tracker]
    /// base_from_tracker`, else the tracker's `position_mm`, else the base origin). The rotation
    /// block does not depend on `p`; the translation's does (it is the translation of `p`).
    pub covariance: Matrix6<f64>,
    /// The setup's noise `sigma` per coordinate of one reading (level multiple 1), m.
    pub noise_std: f64,
    /// The criterion at the setup's noise: `sigma sqrt(tr C_rr)`, rad.
    pub rotation_std: f64,
    /// The same for groups of `n` feasible candidates drawn at random: the median of
    /// `RANDOM_GROUPS`, rad.
    pub random_median_rotation_std: f64,
    /// Candidates drawn.
    pub candidates: usize,
    /// Candidates that pass the cell's checks.
    pub feasible: usize,
    /// How the group was chosen.
    pub method: PoolMethod,
    /// Groups evaluated.
    pub evaluations: usize,
    /// The external axes' values the postures are read at (`station`; SI, the cell's order,
    /// empty without external axes).
    pub external: Vec<f64>,
}

impl Design {
    /// Standard deviations of the translation (m) and of the rotation about the base x, y, z axes
    /// (rad).
    pub fn std(&self) -> Vector6<f64> {
        self.covariance.diagonal().map(f64::sqrt)
    }
}

/// What one candidate posture's points contribute: their count, sum (m) and inertia about the
/// base origin, `sum (|b|^2 I - b b^T)` (m^2).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Moments {
    count: f64,
    sum: Vector3<f64>,
    inertia: Matrix3<f64>,
}

impl Moments {
    /// The moments of `points` (m).
    pub(crate) fn of(points: &[Vector3<f64>]) -> Self {
        Self {
            count: points.len() as f64,
            sum: points.iter().sum(),
            inertia: points.iter().map(inertia).sum(),
        }
    }
}

/// `|b|^2 I - b b^T`.
fn inertia(b: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::identity() * b.norm_squared() - b * b.transpose()
}

/// `sqrt(tr C_rr)` per unit noise of a group from its postures' moments: the inertia about the
/// centroid by the parallel-axis theorem, inverted by Cholesky; `+infinity` when singular
/// (collinear points) or with fewer than
/// [`MIN_POINTS`] points.
pub(crate) fn criterion<'a>(moments: impl Iterator<Item = &'a Moments>) -> f64 {
    let (mut count, mut sum, mut inertia_origin) = (0.0, Vector3::zeros(), Matrix3::zeros());
    for m in moments {
        count += m.count;
        sum += m.sum;
        inertia_origin += m.inertia;
    }
    if count < MIN_POINTS as f64 {
        return f64::INFINITY;
    }
    let centred = inertia_origin - inertia(&sum) / count;
    let scale = centred.trace();
    match centred.cholesky() {
        Some(c) if c.l().diagonal().min() > 1e-7 * scale.sqrt() => c.inverse().trace().sqrt(),
        _ => f64::INFINITY,
    }
}

/// Where a cell's external axes stand while the registration postures are read: each axis at
/// the value of its travel nearest zero (SI, the cell's order; empty without external axes).
pub(crate) fn station(setup: &Setup) -> Vec<f64> {
    setup.robot().external().map_or(Vec::new(), |axes| {
        (axes.axes().iter())
            .map(|a| 0.0f64.clamp(a.lower, a.upper))
            .collect()
    })
}

/// The measuring points of posture `q` with the external axes at `e`, cell frame, m.
pub(crate) fn points(setup: &Setup, q: &Vector6<f64>, e: &[f64]) -> Vec<Vector3<f64>> {
    let frames = setup.robot().frames_at(q, e);
    let tool = &setup.tool().measuring_points;
    tool.iter().map(|p| frames.point(p)).collect()
}

/// Where the tracker frame's origin is, base frame, m: the translation of `[tracker]
/// base_from_tracker`, else the tracker's `position_mm`, else the base origin.
fn tracker_origin(setup: &Setup) -> Vector3<f64> {
    setup.tracker().map_or(Vector3::zeros(), |t| {
        t.base_from_tracker
            .map_or(t.position, |b| b.translation.vector)
    })
}

/// The `n` registration postures of `setup` that minimise the rotation's standard deviation
/// (module docs).
///
/// # Errors
/// [`Error::InvalidField`]: `n` below 1 or above [`MAX_POSTURES`]; `candidates` or `restarts`
/// outside their limits; fewer feasible candidates than `n` (field `postures`, naming the check
/// failed most often); no group of `n` whose points span a plane (field `postures`: one
/// measuring point and `n` below 3, say).
pub fn design(setup: &Setup, n: usize, options: &Options) -> Result<Design> {
    limits::check_count("postures", n, 1, MAX_POSTURES)?;
    limits::check_count("candidates", options.candidates, 1, MAX_CANDIDATES)?;
    let restarts = options.restarts as u64;
    limits::check_integer("restarts", restarts, 1, limits::MAX_POOL_RESTARTS)?;
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let (lower, upper) = (&setup.bounds().lower, &setup.bounds().upper);
    let drawn: Vec<Vector6<f64>> = (0..options.candidates)
        .map(|_| Vector6::from_fn(|a, _| rng.random_range(lower[a]..=upper[a])))
        .collect();
    let checker = Checker::new(setup);
    let e = station(setup);
    let failed: Vec<Option<CheckKind>> = (drawn.par_iter())
        .map(|q| failing(&checker, q, &e))
        .collect();
    let feasible: Vec<Vector6<f64>> = drawn
        .iter()
        .zip(&failed)
        .filter(|(_, f)| f.is_none())
        .map(|(q, _)| *q)
        .collect();
    if feasible.len() < n {
        return Err(too_few_feasible(setup, n, &failed));
    }
    let moments: Vec<Moments> = feasible
        .iter()
        .map(|q| Moments::of(&points(setup, q, &e)))
        .collect();
    let value = |group: &[usize]| criterion(group.iter().map(|&k| &moments[k]));
    let pool_options = PoolOptions {
        seed: options.seed,
        restarts: options.restarts,
        ..PoolOptions::default()
    };
    let chosen = exchange::best(feasible.len(), n, &pool_options, &value);
    let mut group = chosen.group;
    group.sort_unstable();
    if !value(&group).is_finite() {
        return Err(Error::InvalidField {
            field: "postures".into(),
            message: format!(
                "no {n} of the {} feasible candidates put the {} on more than one line: measure more postures",
                feasible.len(),
                stiffid_core::common::words::count(n * setup.tool().measuring_points.len(), "point")
            ),
        });
    }
    let mut postures: Vec<Vector6<f64>> = group.iter().map(|&k| feasible[k]).collect();
    let mut chosen_moments: Vec<Moments> = group.iter().map(|&k| moments[k]).collect();
    polish((setup, &e), &checker, &mut postures, &mut chosen_moments);
    let origin = tracker_origin(setup);
    let all: Vec<Vector3<f64>> = (postures.iter())
        .flat_map(|q| points(setup, q, &e))
        .map(|b| b - origin)
        .collect();
    let covariance = unit_covariance(&all)? * setup.noise().reading_variance;
    let sigma = setup.noise().reading_sd();
    Ok(Design {
        rotation_std: covariance.fixed_view::<3, 3>(3, 3).trace().sqrt(),
        random_median_rotation_std: sigma * random_median(&moments, n, options.seed),
        noise_std: sigma,
        postures,
        covariance,
        candidates: drawn.len(),
        feasible: feasible.len(),
        method: chosen.method,
        evaluations: chosen.evaluations,
        external: e,
    })
}

/// Coordinate search on the chosen postures: each axis angle of each posture in turn moved by
/// `+-` a step (an eighth of the axis's range in the bounds, halved [`POLISH_HALVINGS`] times), a
/// move kept when the criterion falls and the posture still passes the cell's checks (those that
/// apply without the load).
fn polish(
    (setup, e): (&Setup, &[f64]),
    checker: &Checker,
    postures: &mut [Vector6<f64>],
    moments: &mut [Moments],
) {
    let (lower, upper) = (&setup.bounds().lower, &setup.bounds().upper);
    let mut current = criterion(moments.iter());
    for halving in 0..POLISH_HALVINGS {
        let step = (upper - lower) * (0.125 * 0.5f64.powi(halving));
        for _ in 0..POLISH_PASSES {
            let mut moved = false;
            for i in 0..postures.len() {
                for (axis, sign) in (0..6).flat_map(|a| [(a, 1.0), (a, -1.0)]) {
                    let mut q = postures[i];
                    q[axis] = (q[axis] + sign * step[axis]).clamp(lower[axis], upper[axis]);
                    let m = Moments::of(&points(setup, &q, e));
                    let others = moments.iter().enumerate().filter(|(k, _)| *k != i);
                    let v = criterion(others.map(|(_, m)| m).chain([&m]));
                    if exchange::improves(v, current) && failing(checker, &q, e).is_none() {
                        (postures[i], moments[i], current, moved) = (q, m, v, true);
                    }
                }
            }
            if !moved {
                break;
            }
        }
    }
}

/// The first check that `q` fails among those that apply without the load.
fn failing(checker: &Checker, q: &Vector6<f64>, e: &[f64]) -> Option<CheckKind> {
    let f = checker.feasibility_at(q, e);
    let mut failing = f.violations().map(|c| c.kind);
    failing.find(|k| !LOAD_CHECKS.contains(k))
}

/// The median criterion (per unit noise) of [`RANDOM_GROUPS`] groups of `n` candidates drawn
/// with stream 1 of `seed`.
fn random_median(moments: &[Moments], n: usize, seed: u64) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(1);
    let mut values: Vec<f64> = (0..RANDOM_GROUPS)
        .map(|_| {
            let group = rand::seq::index::sample(&mut rng, moments.len(), n);
            criterion(group.iter().map(|k| &moments[k]))
        })
        .collect();
    values.sort_by(f64::total_cmp);
    values[RANDOM_GROUPS / 2]
}

/// The error for fewer feasible candidates than postures asked for.
fn too_few_feasible(setup: &Setup, n: usize, failed: &[Option<CheckKind>]) -> Error {
    let feasible = failed.iter().filter(|f| f.is_none()).count();
    let most = CheckKind::ALL
        .into_iter()
        .map(|k| (k, failed.iter().filter(|f| **f == Some(k)).count()))
        .max_by_key(|&(k, c)| (c, std::cmp::Reverse(k)))
        .filter(|(_, c)| *c > 0);
    let mut why = most.map_or(String::new(), |(k, c)| {
        format!(" (the {k} check failed first in {c})")
    });
    if let (0, Some((k, _))) = (feasible, most) {
        why += &format!("; what decides it: {}", k.remedy(setup));
    }
    Error::InvalidField {
        field: "postures".into(),
        message: format!(
            "{n} asked for, but only {feasible} of the {} candidates drawn in the bounds pass the cell's checks{why}: draw more candidates or widen the bounds",
            failed.len()
        ),
    }
}
