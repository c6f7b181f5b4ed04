//! Design for the candidates of the model comparison ([`crate::identify::compare::pool`]):
//! whether a group of postures identifies each candidate together with the setup's model, and the
//! setup a group is designed on so that it identifies them all (`select --for-candidates`).
//!
//! **Per candidate.** The group's observation matrix under the setup's rope load, one block per
//! load step (the rope wrench scaled by `f_s / F`; one block at the rope load without steps), with
//! the setup's model's columns and then the candidate's, through its law ([`crate::model::Law`]).
//! The group identifies the candidate when this matrix has full column-scaled rank, by the rule of
//! `identify` ([`identifiability`]: singular values above [`crate::identify::model::RANK_TOLERANCE`]
//! times the largest); otherwise the combinations it cannot see are named. How well: the
//! candidate's *separation* `|P psi_c| / |psi_c|`, `psi_c` its column and `P` the projector onto
//! the complement of the model's columns (the last diagonal entry of the Householder QR of the
//! matrix over `|psi_c|`): the sine of the angle between the candidate's deflections over the
//! group and everything the model can produce, 1 when the model cannot mimic any of it, 0 when it
//! reproduces it exactly (`1 / sqrt(VIF)`, the variance inflation factor of the candidate's
//! column; Belsley, Kuh and Welsch, "Regression Diagnostics", 1980, ch. 3). It is free of the
//! units, the noise and the candidate's unknown size; at a given noise the standard deviation of
//! the candidate's compliance is inversely proportional to it.
//!
//! **Lost motion and load-dependent compliance.** With one load level per posture their columns
//! differ from the drive's only through how the load changes from posture to posture: a full rank
//! then identifies them only as well as nothing else changes that way, and
//! [`Verdict::needs_load_steps`] says so; load steps (`[loading] steps_n`) separate them in every
//! posture ([`crate::identify::compare::nonlinear_separation`]).
//!
//! **The design setup.** [`design_setup`] adds every linear candidate to the setup's model, so
//! that the design criteria and searches, which work over any number of parameters, choose a group
//! for the model and the candidates together. A candidate needs a nominal stiffness for the scaled
//! criteria: its own when declared with one, else [`candidate_nominal_stiffness`]: a candidate is
//! asked to be identified as well as a spring as compliant as the drives. The nonlinear candidates
//! stay out of the design: what separates them is the load levels of each posture, which the
//! choice of postures does not give (their verdict on the group is reported all the same).

use crate::identify::compare::{Dropped, Pool};
use crate::identify::model::identifiability;
use crate::math::linalg::householder_qr_columns;
use crate::model::{Kind, Parameter, Spring};
use crate::observation::write_posture_block;
use crate::{Error, Result, Setup};
use nalgebra::{DMatrix, Vector6};

/// How a group identifies one candidate together with the setup's model (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// The candidate as a parameter: its name, kind and unit.
    pub parameter: Parameter,
    /// Its family ([`crate::identify::compare::pool::CANDIDATE_FAMILIES`]).
    pub family: &'static str,
    /// The group identifies the model's parameters and the candidate together.
    pub identified: bool,
    /// `|P psi_c| / |psi_c|`, 0 to 1 (module docs); 0 when not identified.
    pub separation: f64,
    /// The combinations of the model's parameters and the candidate the group cannot separate
    /// (e.g. `0.71 k2 - 0.71 tilt2_x`); empty when identified.
    pub unidentifiable: Vec<String>,
    /// A lost motion or a load-dependent compliance with one load level per posture: identified,
    /// if at all, only through how the load changes from posture to posture (module docs).
    pub needs_load_steps: bool,
}

/// Every candidate of a pool on a group (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Verdicts {
    /// The load levels per posture of the design: the setup's load steps, 1 without.
    pub load_levels: usize,
    /// Each candidate of the pool, in its order.
    pub candidates: Vec<Verdict>,
    /// The combinations of the model's parameters and every linear candidate at once (what
    /// `select --for-candidates` designs for) that the group cannot separate, named: empty when it
    /// identifies them all together, so that any model of a forward selection among them is
    /// identified too.
    pub together: Vec<String>,
    /// The candidates the pool left out, with why ([`Pool::dropped`]).
    pub dropped: Vec<Dropped>,
}

impl Verdicts {
    /// The names of the candidates identified and needing no load steps: those that
    /// `--compare-models` can separate on this group.
    pub fn separable(&self) -> Vec<&str> {
        let ok = |v: &&Verdict| v.identified && !v.needs_load_steps;
        let names = self.candidates.iter().filter(ok);
        names.map(|v| v.parameter.name.as_str()).collect()
    }
}

/// How the group `postures` (axis angles, rad) identifies each candidate of `pool` together with
/// `setup`'s model (module docs).
///
/// # Errors
/// [`Error::NotFinite`] for a group whose observation matrix is not finite.
pub fn verdicts(setup: &Setup, postures: &[Vector6<f64>], pool: &Pool) -> Result<Verdicts> {
    let scales = load_scales(setup);
    let psi = observation(setup, postures, &pool.candidates, &scales);
    let n = setup.model().len();
    let mut names = setup.model().parameters();
    names.push(names[0].clone());
    let candidates = pool.candidates.iter().zip(&pool.families).enumerate();
    let verdicts = candidates.map(|(c, (spring, &family))| {
        let columns: Vec<usize> = (0..n).chain([n + c]).collect();
        let sub = psi.select_columns(&columns);
        let parameter = parameter_of(setup, spring)?;
        names[n] = parameter.clone();
        let rows = sub.nrows().max(n + 1);
        let id = identifiability(&sub.clone().resize_vertically(rows, 0.0))?;
        Ok(Verdict {
            parameter,
            family,
            identified: id.unidentifiable.is_empty(),
            separation: match id.unidentifiable.is_empty() {
                true => separation(sub),
                false => 0.0,
            },
            unidentifiable: id
                .unidentifiable
                .iter()
                .map(|u| u.describe(&names))
                .collect(),
            needs_load_steps: !spring.law.is_linear() && scales.len() < 2,
        })
    });
    let candidates: Vec<Verdict> = verdicts.collect::<Result<_>>()?;
    Ok(Verdicts {
        load_levels: scales.len(),
        together: together(setup, &psi, pool)?,
        candidates,
        dropped: pool.dropped.clone(),
    })
}

/// The combinations of the model's parameters and every linear candidate of `pool` that `psi`
/// (the model's columns, then every candidate's) cannot separate, named.
fn together(setup: &Setup, psi: &DMatrix<f64>, pool: &Pool) -> Result<Vec<String>> {
    let n = setup.model().len();
    let linear: Vec<usize> = (pool.candidates.iter().enumerate())
        .filter(|(_, s)| s.law.is_linear())
        .map(|(c, _)| n + c)
        .collect();
    let columns: Vec<usize> = (0..n).chain(linear.iter().copied()).collect();
    let mut names = setup.model().parameters();
    for &c in &linear {
        names.push(parameter_of(setup, &pool.candidates[c - n])?);
    }
    let sub = psi.select_columns(&columns);
    let rows = sub.nrows().max(columns.len());
    let id = identifiability(&sub.resize_vertically(rows, 0.0))?;
    Ok(id
        .unidentifiable
        .iter()
        .map(|u| u.describe(&names))
        .collect())
}

/// The candidate `spring` as a parameter of the setup's model with it.
fn parameter_of(setup: &Setup, spring: &Spring) -> Result<Parameter> {
    let model = setup.model().with(std::slice::from_ref(spring))?;
    Ok(model
        .parameters()
        .pop()
        .expect("a model with the candidate"))
}

/// The rope wrench's multiple at each load step (`f_s / F`); `[1]` without steps.
fn load_scales(setup: &Setup) -> Vec<f64> {
    match setup.load_steps() {
        [] => vec![1.0],
        steps => steps.iter().map(|f| f / setup.load().load).collect(),
    }
}

/// The observation matrix of `postures` (module docs): per posture and load step, the rows of
/// every measuring point; the columns of `setup`'s model, then one per candidate through its law.
fn observation(
    setup: &Setup,
    postures: &[Vector6<f64>],
    candidates: &[Spring],
    scales: &[f64],
) -> DMatrix<f64> {
    let (arm, robot) = (setup.arm(), setup.robot());
    let points = &setup.tool().measuring_points;
    let (p3, n) = (3 * points.len(), setup.model().len());
    let mut psi = DMatrix::zeros(p3 * postures.len() * scales.len(), n + candidates.len());
    let mut block = DMatrix::zeros(p3, n);
    let mut row = 0;
    for q in postures {
        let frames = robot.frames(q);
        let loading = frames.point(&setup.tool().loading_point);
        for &scale in scales {
            let wrench = setup.rope_wrench(&frames) * scale;
            write_posture_block(arm, &frames, &wrench, &mut block, 0);
            psi.view_mut((row, 0), (p3, n)).copy_from(&block);
            for (c, spring) in candidates.iter().enumerate() {
                let placed = spring.placed(robot, &frames);
                let g = spring.response(&placed, &loading, &wrench);
                for (k, point) in points.iter().enumerate() {
                    let v = placed.velocity(&frames.point(point)) * g;
                    psi.fixed_view_mut::<3, 1>(row + 3 * k, n + c).copy_from(&v);
                }
            }
            row += p3;
        }
    }
    psi
}

/// `|P psi_c| / |psi_c|` of the last column of `psi` against the others (module docs).
fn separation(psi: DMatrix<f64>) -> f64 {
    let n = psi.ncols();
    let norm = psi.column(n - 1).norm();
    if norm == 0.0 || !norm.is_finite() {
        return 0.0;
    }
    let m = psi.nrows().max(n);
    let mut a = psi.resize_vertically(m, 0.0);
    let mut taus = vec![0.0; n];
    householder_qr_columns(a.as_mut_slice(), m, &mut taus);
    (a[(n - 1, n - 1)].abs() / norm).min(1.0)
}

/// The nominal stiffness a candidate without one takes in the design (module docs): for a
/// rotation, the geometric mean of the drives' nominal stiffness (Nm/rad); for a translation,
/// that over the square of the setup's characteristic length (N/m; 1 m without one), the
/// stiffness at the flange of a rotation at that lever arm. `None` without the drives' nominal
/// stiffness.
pub fn candidate_nominal_stiffness(setup: &Setup, kind: Kind) -> Option<f64> {
    let drives = setup.nominal_stiffness()?;
    let mean = drives.iter().map(|k| k.ln()).sum::<f64>() / 6.0;
    let lever = setup.characteristic_length().unwrap_or(1.0);
    Some(match kind {
        Kind::Rotation => mean.exp(),
        Kind::Translation => mean.exp() / (lever * lever),
    })
}

/// `setup` with every linear candidate of `pool` added to its model (module docs), without
/// declared candidates; and the names of the candidates left out of the design (the nonlinear
/// ones).
///
/// # Errors
/// [`Error::InvalidField`] (`candidates`) when the model and the candidates exceed
/// [`crate::common::limits::MAX_VIRTUAL_SPRINGS`] virtual springs (naming the count and asking
/// for fewer with `--candidates`); the setup builder's errors.
pub fn design_setup(setup: &Setup, pool: &Pool) -> Result<(Setup, Vec<String>)> {
    let (linear, nonlinear): (Vec<&Spring>, Vec<&Spring>) =
        pool.candidates.iter().partition(|s| s.law.is_linear());
    let mut springs = setup.model().springs().to_vec();
    springs.extend(linear.into_iter().map(|s| {
        Spring {
            nominal_stiffness: s
                .nominal_stiffness
                .or_else(|| candidate_nominal_stiffness(setup, s.kind)),
            ..s.clone()
        }
    }));
    let most = crate::common::limits::MAX_VIRTUAL_SPRINGS;
    if springs.len() > most {
        return Err(Error::InvalidField {
            field: "candidates".into(),
            message: format!(
                "the model's virtual springs and the linear candidates are {}, a design takes at most {most}: name fewer candidates",
                springs.len()
            ),
        });
    }
    let design = (setup.to_builder())
        .with_virtual_springs(springs)
        .with_candidate_springs(Vec::new())
        .build()?;
    Ok((design, nonlinear.iter().map(|s| s.name.clone()).collect()))
}
