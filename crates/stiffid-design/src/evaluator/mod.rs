//! Fast evaluation of the design criteria, for the posture search.
//!
//! [`Evaluator::new`] precomputes what does not depend on the postures (the scaling `h / sigma`,
//! the measuring points' factor `R_P`, the observation rows of the test postures). Each posture's
//! forward kinematics is computed once ([`Evaluator::posture`]) and gives its compact block
//! `C = R_P J_b diag(tau)` (`min(3p, 6) x 6`, with `B^T B = C^T C` for its `3p x 6` block B of
//! `Psi`: an orthogonal change of rows, see `observation::points_factor`) and, only when a criterion
//! needs it, the TCP dexterity; the search reuses the terms of postures a finite-difference step did
//! not move. The stacked compact blocks have the triangular factor `R` of `Psi` (up to the signs of
//! its rows, which no criterion sees); they are factored by [`Factor::try_new`] (Householder, with
//! its rank rule: `+infinity` for a rank-deficient group), and only what the chosen criterion needs
//! is computed from `R`:
//! - `cond_2(Psi)`, `cond_2(S)`: singular values of `R`, `R diag(h) / sigma` (one-sided Jacobi);
//! - `d-optimal`: `prod_k |R_kk h_k / sigma|^(-1/6)`;
//! - `relative-a`, relative standard deviations: row norms of `(R diag(h) / sigma)^-1`;
//! - `test-pose`: `sigma |A R^-1|_F / sqrt(T)`, A the `T` test postures' rows, as
//!   `sigma |R_A R^-1|_F / sqrt(T)` with `A = Q_A R_A` factored once (`Q_A` keeps the norm).
//!
//! A model with virtual springs ([`stiffid_core::model`]) has `n > 6` parameters: each posture's compact
//! block gains one column per spring (`springs`), `R` is `n x n` and the criteria are those of
//! `wide` (the same formulas over n columns). The six drives alone keep the fixed-size path above.

use super::criteria::{predicted_deviation_pct, tcp_dexterity, Criterion, Evaluation};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};
use std::cell::OnceCell;
use stiffid_core::math::householder::{self, triangular_factor};
use stiffid_core::math::jacobi::{cond, cond_n};
use stiffid_core::math::lsq::Factor;
use stiffid_core::observation::{compact_posture_block, points_factor, rope_observation_matrix};
use stiffid_core::setup::Setup;
use stiffid_core::Frames;
use stiffid_identify::svd::{identifiability, Identifiability};
use wide::WideGroup;

mod gradient;
pub(crate) use gradient::MaxSplit;
mod springs;
mod wide;

/// Evaluates design criteria of groups of postures for one setup.
#[derive(Debug, Clone)]
pub struct Evaluator<'a> {
    setup: &'a Setup,
    /// `h / sigma` (rad/Nm per m): the column scaling of `S`.
    scaling: Vector6<f64>,
    /// `R_P` of the measuring points (`observation::points_factor`) and the number of its rows
    /// that can be non-zero, `min(3p, 6)`: the rows of a posture's compact block.
    points_factor: Matrix6<f64>,
    compact_rows: usize,
    /// `R_A` (6x6, upper triangular) of the Householder QR `A = Q_A R_A` of the test postures'
    /// observation rows `A` (`3pT x 6`, under their rope-mass load): `A^T A = R_A^T R_A`.
    test_factor: Matrix6<f64>,
    /// For a model with virtual springs, what its `n` parameters need; `None` for the drives alone.
    wide: Option<Wide>,
}

/// The scaling and the test postures' factor over all `n` parameters of a model with virtual
/// springs.
#[derive(Debug, Clone)]
struct Wide {
    /// `h / sigma` of every parameter (drives, then springs).
    scaling: DVector<f64>,
    /// `R_A` (`n x n`, upper triangular) of the test postures' observation rows.
    test_factor: DMatrix<f64>,
}

/// What one posture contributes to a group: its compact block of `Psi` (module docs) and its TCP
/// dexterity.
#[derive(Debug, Clone)]
pub(crate) struct PostureTerms {
    frames: Frames,
    compact: Matrix6<f64>,
    /// The compact columns of the model's virtual springs (column-major, six rows each; empty for
    /// the drives alone).
    springs: Vec<f64>,
    /// `k(J_N)` of the TCP (Eq. 21), computed on first use.
    dexterity: OnceCell<f64>,
}

impl<'a> Evaluator<'a> {
    /// An evaluator for `setup`.
    pub fn new(setup: &'a Setup) -> Self {
        Self {
            setup,
            // Without a nominal stiffness, 1 rad/Nm: the criteria that need it are NaN then.
            scaling: setup.nominal_compliance().unwrap_or(Vector6::repeat(1.0))
                / setup.displacement_variance().sqrt(),
            points_factor: points_factor(setup.tool()),
            compact_rows: (3 * setup.tool().measuring_points.len()).min(6),
            test_factor: match setup.model().is_drives_only() {
                true => triangular_factor(rope_observation_matrix(setup, setup.test_postures())),
                false => Matrix6::zeros(),
            },
            wide: (!setup.model().is_drives_only()).then(|| Wide::new(setup)),
        }
    }

    /// The number of parameters of the setup's model (6 for the drives alone).
    pub(crate) fn parameters(&self) -> usize {
        self.wide.as_ref().map_or(6, |w| w.scaling.len())
    }

    /// The setup evaluated.
    pub(crate) fn setup(&self) -> &Setup {
        self.setup
    }

    /// The value of `criterion` for `postures` (axis angles, rad), equal to
    /// [`Evaluation::value`] of [`Evaluator::evaluation`]: `+infinity` for a group whose observation
    /// matrix is rank deficient; NaN only for a criterion the setup lacks a field for
    /// ([`Criterion::check`]).
    pub fn value(&self, criterion: Criterion, postures: &[Vector6<f64>]) -> f64 {
        if !criterion.serves(self.setup) {
            return f64::NAN;
        }
        if criterion == Criterion::Classical {
            let mut classical = 0.0;
            self.for_each_frames(postures, |_, frames| {
                classical = f64::max(classical, tcp_dexterity(self.setup, frames));
            });
            return classical;
        }
        // Each posture's compact rows straight into the stack; its dexterity only for zhang2021.
        let mut classical = 0.0;
        let mut stack = DMatrix::zeros(self.compact_rows * postures.len(), self.parameters());
        let mut springs = vec![0.0; 6 * (self.parameters() - 6)];
        self.for_each_frames(postures, |i, frames| {
            self.write_compact(frames, &mut stack, i);
            if !springs.is_empty() {
                springs::write_compact_columns(
                    self.setup,
                    frames,
                    &self.points_factor,
                    &mut springs,
                );
                self.write_springs(&springs, &mut stack, i);
            }
            if criterion == Criterion::Zhang2021 {
                classical = f64::max(classical, tcp_dexterity(self.setup, frames));
            }
        });
        match self.factor(stack) {
            Some(group) => self.score(criterion, &group, || classical),
            None => f64::INFINITY,
        }
    }

    /// Shows `each` the index and forward kinematics of every posture in turn (one `Frames`
    /// updated in place).
    fn for_each_frames(&self, postures: &[Vector6<f64>], mut each: impl FnMut(usize, &Frames)) {
        let robot = self.setup.robot();
        let Some(first) = postures.first() else {
            return;
        };
        let mut frames = robot.frames(first);
        each(0, &frames);
        for (i, q) in postures.iter().enumerate().skip(1) {
            robot.update_frames(q, &mut frames);
            each(i, &frames);
        }
    }

    /// The terms of one posture (axis angles, rad), to reuse across groups that share it (finite
    /// differences change one posture at a time).
    pub(crate) fn posture(&self, q: &Vector6<f64>) -> PostureTerms {
        let frames = self.setup.robot().frames(q);
        let compact = compact_posture_block(self.setup, &frames, &self.points_factor);
        let mut springs = vec![0.0; 6 * (self.parameters() - 6)];
        if !springs.is_empty() {
            springs::write_compact_columns(self.setup, &frames, &self.points_factor, &mut springs);
        }
        PostureTerms {
            frames,
            compact,
            springs,
            dexterity: OnceCell::new(),
        }
    }

    /// The value of `criterion` for the group of postures whose terms are given: the same as
    /// [`Evaluator::value`] of those postures.
    pub(crate) fn value_of(&self, criterion: Criterion, terms: &[&PostureTerms]) -> f64 {
        if !criterion.serves(self.setup) {
            return f64::NAN;
        }
        if criterion == Criterion::Classical {
            return self.classical(terms);
        }
        match self.group(terms) {
            Some(group) => self.score(criterion, &group, || self.classical(terms)),
            None => f64::INFINITY,
        }
    }

    /// The information matrix `S_i^T S_i` (`n x n`, unitless at noise level 1) of one posture's
    /// terms: a group's `S^T S` is the sum over its postures. For exchange algorithms
    /// ([`super::pool`]).
    pub(crate) fn information(&self, terms: &PostureTerms) -> Information {
        match &self.wide {
            None => {
                let d = Matrix6::from_diagonal(&self.scaling);
                Information::Six(d * terms.compact.tr_mul(&terms.compact) * d)
            }
            Some(wide) => {
                let mut c = self.wide_compact(terms);
                for (j, s) in wide.scaling.iter().enumerate() {
                    c.column_mut(j).scale_mut(*s);
                }
                Information::Wide(wide::gram(&c))
            }
        }
    }

    /// The TCP dexterity `k(J_N)` of one posture's terms (Eq. 21).
    pub(crate) fn dexterity(&self, terms: &PostureTerms) -> f64 {
        *terms
            .dexterity
            .get_or_init(|| tcp_dexterity(self.setup, &terms.frames))
    }

    /// The value of `criterion` for a group given its information matrix `S^T S` (a sum of
    /// [`Evaluator::information`]) and its classical index: the group's triangular factor is
    /// the Cholesky factor of `S^T S` (equal to `R_s` up to the signs of its rows, which no criterion
    /// sees). `+infinity` when `S^T S` is not positive definite. Equal to [`Evaluator::value`] of
    /// the group up to rounding (the Cholesky factor of `S^T S` loses about `cond(S)^2 eps`
    /// relative in the smallest singular value, which ranks groups as well; reports re-evaluate).
    pub(crate) fn value_from_information(
        &self,
        criterion: Criterion,
        information: &Information,
        classical: f64,
    ) -> f64 {
        let group = match (information, &self.wide) {
            (Information::Six(information), _) => information
                .cholesky()
                .and_then(|c| Group::from_scaled(c.l().transpose(), &self.scaling))
                .map(Factored::Six),
            (Information::Wide(information), Some(wide)) => wide::cholesky_upper(information)
                .and_then(|rs| WideGroup::from_scaled(rs, &wide.scaling))
                .map(Factored::Wide),
            (Information::Wide(_), None) => None,
        };
        match group {
            Some(group) => self.score(criterion, &group, || classical),
            None => f64::INFINITY,
        }
    }

    /// The value of `criterion` (not [`Criterion::Classical`] alone) from a full-rank group's
    /// factor; `classical` gives the classical index when the criterion needs it.
    fn score(&self, criterion: Criterion, group: &Factored, classical: impl Fn() -> f64) -> f64 {
        finite(match criterion {
            Criterion::Classical => classical(),
            Criterion::Zhang2021 => classical() * group.cond_psi(),
            Criterion::ScaledCond => group.cond_scaled(),
            Criterion::DOptimal => group.d_optimal(),
            Criterion::RelativeA => group.relative_a(),
            Criterion::TestPose => self.test_pose(group),
        })
    }

    /// Every criterion and the predicted deviation rates of `postures` (axis angles, rad); NaN for
    /// what the setup lacks a field for ([`Evaluation`]).
    pub fn evaluation(&self, postures: &[Vector6<f64>]) -> Evaluation {
        let terms: Vec<PostureTerms> = postures.iter().map(|q| self.posture(q)).collect();
        let refs: Vec<&PostureTerms> = terms.iter().collect();
        let classical = self.classical(&refs);
        let levels = &self.setup.noise().levels;
        let identifiability = self.identifiability(&refs);
        let Some(group) = self.group(&refs) else {
            let inf = f64::INFINITY;
            return Evaluation {
                classical,
                zhang2021: inf,
                scaled_cond: inf,
                d_optimal: inf,
                relative_a: inf,
                test_pose: inf,
                cond_psi: inf,
                relative_std: Vector6::repeat(inf),
                spring_relative_std: vec![inf; self.parameters() - 6],
                predicted_deviation_pct: vec![[inf; 6]; levels.len()],
                identifiability,
            }
            .without_missing(self.setup);
        };
        let cond_psi = finite(group.cond_psi());
        let all_std = group.relative_std();
        let relative_std = Vector6::from_column_slice(&all_std[..6]);
        Evaluation {
            classical,
            zhang2021: finite(classical * cond_psi),
            scaled_cond: finite(group.cond_scaled()),
            d_optimal: group.d_optimal(),
            relative_a: group.relative_a(),
            test_pose: self.test_pose(&group),
            cond_psi,
            relative_std,
            spring_relative_std: all_std[6..].to_vec(),
            predicted_deviation_pct: levels
                .iter()
                .map(|&m| predicted_deviation_pct(&relative_std, m))
                .collect(),
            identifiability,
        }
        .without_missing(self.setup)
    }

    /// The relative standard deviations of the six drives (Eq. 19, noise level 1) of `postures`
    /// (axis angles, rad) without each posture in turn (leave-one-out): [`Evaluation::relative_std`]
    /// of the others, infinite where they do not identify every parameter. Each posture's terms
    /// are computed once, so the work is one factorisation of `n - 1` postures per posture.
    pub fn relative_std_without_each(&self, postures: &[Vector6<f64>]) -> Vec<Vector6<f64>> {
        let terms: Vec<PostureTerms> = postures.iter().map(|q| self.posture(q)).collect();
        (0..terms.len())
            .map(|i| {
                let others: Vec<&PostureTerms> = (terms.iter().enumerate())
                    .filter(|(j, _)| *j != i)
                    .map(|(_, t)| t)
                    .collect();
                self.group(&others)
                    .map_or(Vector6::repeat(f64::INFINITY), |g| {
                        Vector6::from_column_slice(&g.relative_std()[..6])
                    })
            })
            .collect()
    }

    /// The classical index `max_i k(J_N)_i` of the postures' terms (Eq. 21; 0 without terms).
    pub(crate) fn classical(&self, terms: &[&PostureTerms]) -> f64 {
        terms.iter().map(|t| self.dexterity(t)).fold(0.0, f64::max)
    }

    /// The stacked compact blocks of the postures' terms (`min(3p, 6)` rows per posture, one
    /// column per parameter).
    fn stack(&self, terms: &[&PostureTerms]) -> DMatrix<f64> {
        let r = self.compact_rows;
        let mut stack = DMatrix::zeros(r * terms.len(), self.parameters());
        for (i, t) in terms.iter().enumerate() {
            stack
                .view_mut((r * i, 0), (r, 6))
                .copy_from(&t.compact.rows(0, r));
            self.write_springs(&t.springs, &mut stack, i);
        }
        stack
    }

    /// Which parameters the postures' terms identify: [`identifiability`] of their stacked
    /// compact blocks (the column norms and Gram matrix of `Psi`), padded with zero rows to at
    /// least one per parameter; nothing for non-finite blocks.
    fn identifiability(&self, terms: &[&PostureTerms]) -> Identifiability {
        let stack = self.stack(terms);
        let n = stack.ncols();
        let rows = stack.nrows().max(n);
        identifiability(&stack.resize_vertically(rows, 0.0)).unwrap_or_else(|_| Identifiability {
            rank: 0,
            scaled_cond: f64::INFINITY,
            unidentifiable: Vec::new(),
            identified: vec![false; n],
        })
    }

    /// The factor of the group's `Psi` (the compact blocks stacked), `None` if rank deficient.
    fn group(&self, terms: &[&PostureTerms]) -> Option<Factored> {
        self.factor(self.stack(terms))
    }

    /// The compact block (`6 x n`, drives then springs) of one posture's terms.
    fn wide_compact(&self, terms: &PostureTerms) -> DMatrix<f64> {
        let springs = terms.springs.len() / 6;
        DMatrix::from_fn(6, 6 + springs, |i, j| match j {
            0..6 => terms.compact[(i, j)],
            _ => terms.springs[6 * (j - 6) + i],
        })
    }

    /// Writes the compact block of the posture `frames` into rows `r i..r (i + 1)` of `stack`.
    fn write_compact(&self, frames: &Frames, stack: &mut DMatrix<f64>, i: usize) {
        let r = self.compact_rows;
        let c = compact_posture_block(self.setup, frames, &self.points_factor);
        stack.view_mut((r * i, 0), (r, 6)).copy_from(&c.rows(0, r));
    }

    /// Writes the springs' compact columns (`springs`, column-major, six rows each) into rows
    /// `r i..r (i + 1)` of columns `6..` of `stack`.
    fn write_springs(&self, springs: &[f64], stack: &mut DMatrix<f64>, i: usize) {
        let r = self.compact_rows;
        for (s, column) in springs.chunks_exact(6).enumerate() {
            for (k, v) in column[..r].iter().enumerate() {
                stack[(r * i + k, 6 + s)] = *v;
            }
        }
    }

    /// The factor of a group's `Psi` from its stacked compact blocks (same `R` up to the signs of its
    /// rows, same column norms), `None` if rank deficient.
    fn factor(&self, psi: DMatrix<f64>) -> Option<Factored> {
        if let Some(wide) = &self.wide {
            let m = psi.nrows();
            return WideGroup::factor(Vec::from(psi.data), m, &wide.scaling).map(Factored::Wide);
        }
        let factor = Factor::try_new(psi).ok()?;
        let (r, r_inv) = (*factor.r(), *factor.r_inv());
        // R diag(h / sigma) and its inverse diag(sigma / h) R^-1: column and row scalings.
        let mut rs = r;
        let mut rs_inv = r_inv;
        for j in 0..6 {
            rs.column_mut(j).scale_mut(self.scaling[j]);
            rs_inv.row_mut(j).scale_mut(1.0 / self.scaling[j]);
        }
        Some(Factored::Six(Group {
            r,
            rs,
            rs_inv,
            r_inv,
        }))
    }

    /// `sigma sqrt(mean_t tr(A_t (Psi^T Psi)^-1 A_t^T)) = sigma |A R^-1|_F / sqrt(T)`, m; 0 without
    /// test postures.
    fn test_pose(&self, group: &Factored) -> f64 {
        let t = self.setup.test_postures().len();
        if t == 0 {
            return 0.0;
        }
        let sum = match group {
            Factored::Six(g) => self.test_weight(g).norm_squared(),
            Factored::Wide(g) => self.wide_test_weight(g).norm_squared(),
        };
        finite(self.setup.displacement_variance().sqrt() * (sum / t as f64).sqrt())
    }

    /// `Z = R_A R^-1`: `|Z|_F = |A R^-1|_F` and `Z^T Z = R^-T A^T A R^-1`.
    fn test_weight(&self, group: &Group) -> Matrix6<f64> {
        self.test_factor * group.r_inv
    }

    /// [`Evaluator::test_weight`] over the `n` parameters of a model with virtual springs.
    fn wide_test_weight(&self, group: &WideGroup) -> DMatrix<f64> {
        let wide = self
            .wide
            .as_ref()
            .expect("a wide group has a wide evaluator");
        wide::product(&wide.test_factor, &group.r_inv)
    }
}

impl Wide {
    fn new(setup: &Setup) -> Self {
        let n = setup.model().len();
        let scaling = setup
            .model_nominal_compliance()
            .unwrap_or_else(|| DVector::repeat(n, 1.0))
            / setup.displacement_variance().sqrt();
        let a = rope_observation_matrix(setup, setup.test_postures());
        let m = a.nrows().max(n);
        let mut a = a.resize_vertically(m, 0.0);
        householder::qr(a.as_mut_slice(), m, n);
        let test_factor = DMatrix::from_fn(n, n, |i, j| if i <= j { a[(i, j)] } else { 0.0 });
        Self {
            scaling,
            test_factor,
        }
    }
}

/// The information matrix `S_i^T S_i` of a posture or a group ([`Evaluator::information`]).
// The six-drive variant stays inline: it is the fast path of the search and the pool.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Information {
    /// The six drives alone.
    Six(Matrix6<f64>),
    /// A model with virtual springs (`n x n`).
    Wide(DMatrix<f64>),
}

impl Information {
    /// The sum of `terms` (in order, from zero); `None` without terms.
    pub(crate) fn sum<'a>(mut terms: impl Iterator<Item = &'a Information>) -> Option<Self> {
        let first = terms.next()?;
        Some(match first {
            Information::Six(m) => {
                Information::Six(terms.fold(Matrix6::zeros() + m, |acc, t| match t {
                    Information::Six(t) => acc + t,
                    Information::Wide(_) => acc,
                }))
            }
            Information::Wide(m) => Information::Wide(terms.fold(m.clone(), |acc, t| match t {
                Information::Wide(t) => acc + t,
                Information::Six(_) => acc,
            })),
        })
    }
}

/// A full-rank group's factor: six columns (the drives alone) or `n` ([`WideGroup`]).
// The six-drive variant stays inline: it is the fast path of the search.
#[allow(clippy::large_enum_variant)]
enum Factored {
    Six(Group),
    Wide(WideGroup),
}

impl Factored {
    /// `cond_2(Psi)`.
    fn cond_psi(&self) -> f64 {
        match self {
            Factored::Six(g) => cond(&g.r),
            Factored::Wide(g) => cond_n(&g.r),
        }
    }

    /// `cond_2(S)`.
    fn cond_scaled(&self) -> f64 {
        match self {
            Factored::Six(g) => cond(&g.rs),
            Factored::Wide(g) => cond_n(&g.rs),
        }
    }

    fn d_optimal(&self) -> f64 {
        match self {
            Factored::Six(g) => g.d_optimal(),
            Factored::Wide(g) => g.d_optimal(),
        }
    }

    fn relative_a(&self) -> f64 {
        match self {
            Factored::Six(g) => g.relative_a(),
            Factored::Wide(g) => g.relative_a(),
        }
    }

    /// The relative standard deviation of every parameter.
    fn relative_std(&self) -> Vec<f64> {
        match self {
            Factored::Six(g) => g.relative_std().as_slice().to_vec(),
            Factored::Wide(g) => g.relative_std(),
        }
    }
}

/// The triangular factor of a full-rank group: `Psi = Q R` and `S = Q R_s`, `R_s = R diag(h) / sigma`.
struct Group {
    r: Matrix6<f64>,
    r_inv: Matrix6<f64>,
    rs: Matrix6<f64>,
    rs_inv: Matrix6<f64>,
}

impl Group {
    /// The group of the upper triangular `R_s` (`scaling` = `h / sigma`); `None` if `R_s` is
    /// singular.
    fn from_scaled(rs: Matrix6<f64>, scaling: &Vector6<f64>) -> Option<Group> {
        let rs_inv = rs.solve_upper_triangular(&Matrix6::identity())?;
        Some(Group {
            r: rs * Matrix6::from_diagonal(&scaling.map(|s| 1.0 / s)),
            r_inv: Matrix6::from_diagonal(scaling) * rs_inv,
            rs,
            rs_inv,
        })
    }

    /// `sqrt([(S^T S)^-1]_jj)`: the row norms of `R_s^-1` (`(S^T S)^-1 = R_s^-1 R_s^-T`).
    fn relative_std(&self) -> Vector6<f64> {
        Vector6::from_fn(|j, _| finite(self.rs_inv.row(j).norm()))
    }

    /// `det((S^T S)^-1)^(1/12) = prod_k |R_s,kk|^(-1/6)`.
    fn d_optimal(&self) -> f64 {
        let log_det: f64 = self.rs.diagonal().iter().map(|d| d.abs().ln()).sum();
        finite((-log_det / 6.0).exp())
    }

    /// `sqrt(tr((S^T S)^-1) / 6) = |R_s^-1|_F / sqrt(6)`.
    fn relative_a(&self) -> f64 {
        finite(self.rs_inv.norm() / 6f64.sqrt())
    }
}

/// `v`, or `+infinity` if it is not finite.
fn finite(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        f64::INFINITY
    }
}

/// Every criterion of a group of postures (axis angles, rad); see [`Evaluator`] for how they are
/// computed, and to evaluate many groups of one setup.
///
/// # Examples
/// A seeded group of 8 postures on the paper's setup: the relative-A criterion is the RMS of the
/// relative standard deviations, and the predicted deviation rate grows as the square root of the
/// noise level (levels 0.5 and 2.0: a factor of 2).
/// ```
/// use stiffid_design::{evaluate, random_group, Criterion};
/// let setup = stiffid_core::setup::builtin("zhang2021-comau-nj165")?;
/// let e = evaluate(&setup, &random_group(&setup, 8, 1));
/// let rms = e.relative_std.norm() / 6f64.sqrt();
/// assert!((e.value(Criterion::RelativeA) - rms).abs() < 1e-12 * rms);
/// let (low, high) = (e.predicted_deviation_pct[0], e.predicted_deviation_pct[3]);
/// assert!((0..6).all(|j| (high[j] / low[j] - 2.0).abs() < 1e-12));
/// # Ok::<(), stiffid_core::Error>(())
/// ```
pub fn evaluate(setup: &Setup, postures: &[Vector6<f64>]) -> Evaluation {
    Evaluator::new(setup).evaluation(postures)
}

#[cfg(test)]
mod tests;
