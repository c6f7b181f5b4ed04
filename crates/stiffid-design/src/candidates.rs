//! Design for the candidates of the model comparison (`stiffid_identify::compare::pool`):
//! whether a group of postures identifies each candidate together with the setup's model, and the
//! setup a group is designed on so that it identifies them all (`select --for-candidates`).
//!
//! **Per candidate.** The group's observation matrix under the setup's rope load, one block per
//! load step (the rope wrench scaled by `f_s / F`; one block at the rope load without steps), with
//! the setup's model's columns and then the candidate's, through its law ([`stiffid_core::model::Law`]).
//! The group identifies the candidate when this matrix has full column-scaled rank, by the rule of
//! `identify` ([`identifiability`]: singular values above `stiffid_identify::svd::RANK_TOLERANCE`
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
//! posture ([`stiffid_identify::compare::nonlinear_separation`]).
//!
//! **The design setup.** [`design_setup`] adds the linear candidates to the setup's model, so
//! that the design criteria and searches, which work over any number of parameters, choose a group
//! for the model and the candidates together. Not every set of candidates can be identified
//! together by any group: `designable` keeps, in the pool's order, each that a generic group
//! separates from the model and the candidates kept before it, and names the others with the
//! combination no group can see. A candidate needs a nominal stiffness for the scaled
//! criteria: its own when declared with one, else `candidate_nominal_stiffness`: a candidate is
//! asked to be identified as well as a spring as compliant as the drives. The nonlinear candidates
//! stay out of the design: what separates them is the load levels of each posture, which the
//! choice of postures does not give (their verdict on the group is reported all the same).

use nalgebra::{DMatrix, Vector6};
use stiffid_core::math::householder;
use stiffid_core::model::{Kind, Parameter, Spring};
use stiffid_core::observation::write_posture_block;
use stiffid_core::{Error, Result, Setup};
use stiffid_identify::compare::{default_pool, pool_by_name, Dropped, Pool};
use stiffid_identify::svd::identifiability;

/// How a group identifies one candidate together with the setup's model (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// The candidate as a parameter: its name, kind and unit.
    pub parameter: Parameter,
    /// Its family (`stiffid_identify::compare::pool::CANDIDATE_FAMILIES`).
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
    /// The linear candidates a design can identify together with the model:
    /// what `select --for-candidates` designs for.
    pub designable: Designable,
    /// The combinations of the model's parameters and every designable candidate at once that
    /// the group cannot separate, named: empty when it identifies them all together, so that any
    /// model of a forward selection among them is identified too.
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
    let designable = designable(setup, pool)?;
    Ok(Verdicts {
        load_levels: scales.len(),
        together: unseparated(setup, &psi, pool, &designable.kept)?,
        designable,
        candidates,
        dropped: pool.dropped.clone(),
    })
}

/// The linear candidates of a pool that a design can identify together with the model, and
/// those it cannot (module docs, "The design setup").
#[derive(Debug, Clone, PartialEq)]
pub struct Designable {
    /// Their indices in the pool, in its order.
    pub kept: Vec<usize>,
    /// The linear candidates left out: a combination of the model's parameters and the earlier
    /// kept candidates at every posture of the probe group, with that combination.
    pub left_out: Vec<Dropped>,
}

/// The postures of the seeded group over the setup's bounds that [`designable`] probes.
pub(crate) const PROBE_POSTURES: usize = 60;

/// The seed of that group ([`crate::random_group`]).
pub(crate) const PROBE_SEED: u64 = 1;

/// The linear candidates of `pool`, in its order, that a design can identify together with the
/// setup's model: each is kept unless the seeded group of [`PROBE_POSTURES`] postures over the
/// setup's bounds (without the cell) cannot separate it from the model and the candidates kept
/// before it (then no group can: a generic group separates whatever any group does). Several
/// candidates can be jointly dependent though none duplicates another: an equal compliance along
/// the base's three axes and along the tool's three axes deflects every point by the same `c f`.
///
/// # Errors
/// [`Error::NotFinite`] for a non-finite observation matrix.
pub(crate) fn designable(setup: &Setup, pool: &Pool) -> Result<Designable> {
    let probe = crate::random_group(&setup.without_cell(), PROBE_POSTURES, PROBE_SEED);
    let psi = observation(setup, &probe, &pool.candidates, &[1.0]);
    let n = setup.model().len();
    let mut names = setup.model().parameters();
    for spring in &pool.candidates {
        names.push(parameter_of(setup, spring)?);
    }
    let mut out = Designable {
        kept: Vec::new(),
        left_out: Vec::new(),
    };
    for (c, spring) in pool.candidates.iter().enumerate() {
        if !spring.law.is_linear() {
            continue;
        }
        let kept = out.kept.iter().map(|k| n + k);
        let columns: Vec<usize> = (0..n).chain(kept).chain([n + c]).collect();
        let id = identifiability(&psi.select_columns(&columns))?;
        match id.unidentifiable.first() {
            None => out.kept.push(c),
            Some(u) => {
                let named: Vec<Parameter> = columns.iter().map(|&j| names[j].clone()).collect();
                out.left_out.push(Dropped {
                    name: spring.name.clone(),
                    reason: format!(
                        "no group separates it from the model and the candidates before it: {} deflects nothing",
                        u.describe(&named)
                    ),
                });
            }
        }
    }
    Ok(out)
}

/// The combinations of the model's parameters and the candidates `kept` (indices in `pool`)
/// that `psi` (the model's columns, then every candidate's) cannot separate, named.
fn unseparated(
    setup: &Setup,
    psi: &DMatrix<f64>,
    pool: &Pool,
    kept: &[usize],
) -> Result<Vec<String>> {
    let n = setup.model().len();
    let mut names = setup.model().parameters();
    for &c in kept {
        names.push(parameter_of(setup, &pool.candidates[c])?);
    }
    let columns: Vec<usize> = (0..n).chain(kept.iter().map(|c| n + c)).collect();
    let sub = psi.select_columns(&columns);
    let rows = sub.nrows().max(columns.len());
    let id = identifiability(&sub.resize_vertically(rows, 0.0))?;
    Ok(id
        .unidentifiable
        .iter()
        .map(|u| u.describe(&names))
        .collect())
}

/// The pool of the candidates `names` ([`pool_by_name`]: families or single candidates), the
/// default pool ([`default_pool`]) for `None`.
///
/// # Errors
/// Those of [`pool_by_name`].
pub fn pool(setup: &Setup, names: Option<&[String]>) -> Result<Pool> {
    match names {
        Some(names) => pool_by_name(setup, names),
        None => Ok(default_pool(setup)),
    }
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
                let placed = spring.placed(&frames);
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
    householder::qr(a.as_mut_slice(), m, n);
    (a[(n - 1, n - 1)].abs() / norm).min(1.0)
}

/// The nominal stiffness a candidate without one takes in the design (module docs): for a
/// rotation, the geometric mean of the drives' nominal stiffness (Nm/rad); for a translation,
/// that over the square of the setup's characteristic length (N/m; 1 m without one), the
/// stiffness at the flange of a rotation at that lever arm. `None` without the drives' nominal
/// stiffness.
pub(crate) fn candidate_nominal_stiffness(setup: &Setup, kind: Kind) -> Option<f64> {
    let drives = setup.nominal_stiffness()?;
    let mean = drives.iter().map(|k| k.ln()).sum::<f64>() / 6.0;
    let lever = setup.characteristic_length().unwrap_or(1.0);
    Some(match kind {
        Kind::Rotation => mean.exp(),
        Kind::Translation => mean.exp() / (lever * lever),
    })
}

/// `setup` with every designable candidate of `pool` (`designable`) added to its model
/// (module docs), without declared candidates; and the designable candidates.
///
/// # Errors
/// [`Error::InvalidOption`] ([`stiffid_core::JobOption::Candidates`]) when the model and the candidates exceed
/// [`stiffid_core::common::limits::MAX_VIRTUAL_SPRINGS`] virtual springs (naming the count and asking
/// for fewer with `--candidates`); the setup builder's errors.
pub fn design_setup(setup: &Setup, pool: &Pool) -> Result<(Setup, Designable)> {
    let designable = designable(setup, pool)?;
    let kept = designable.kept.iter().map(|&c| &pool.candidates[c]);
    let mut springs = setup.model().springs().to_vec();
    springs.extend(kept.map(|s| {
        Spring {
            nominal_stiffness: s
                .nominal_stiffness
                .or_else(|| candidate_nominal_stiffness(setup, s.kind)),
            ..s.clone()
        }
    }));
    let most = stiffid_core::common::limits::MAX_VIRTUAL_SPRINGS;
    if springs.len() > most {
        return Err(Error::InvalidOption {
            option: stiffid_core::JobOption::Candidates,
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
    Ok((design, designable))
}

/// The fewest postures that can identify the `parameters` parameters of a design on `setup`:
/// each posture's rows have rank at most `min(3 p, 6)` (`p` measuring points on the flange, a
/// rigid motion of six components).
pub fn fewest_postures(setup: &Setup, parameters: usize) -> usize {
    let rank = (3 * setup.tool().measuring_points.len()).min(6);
    parameters.div_ceil(rank)
}
