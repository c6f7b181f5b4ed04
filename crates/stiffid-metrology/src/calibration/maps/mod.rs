//! Which joint error maps a calibration fits: joints, harmonics and ridge chosen by
//! cross-validation inside the fitted readings, and the held-out gain of that choice measured by
//! an outer cross-validation around it (nested: the figure quoted is never the one the choice was
//! tuned on).
//!
//! # The candidates
//! A joint's map ([`stiffid_core::robot::ErrorMap`]) of `H` harmonics, `H` in 4, 8, 16 or 32, with
//! the ridge `mu` in `RIDGES` ([`crate::calibration::fit::Options::ridge`]: a penalty of `mu` per
//! reading on a scaled coefficient). `--maps J1,J3:16` fixes the joints and harmonics (a bare joint
//! takes 16) and chooses the ridge alone. Where the readings carry the directions of approach, a
//! joint's backlash term is a candidate too (one column,
//! [`crate::calibration::error_model::Target::Backlash`]): `J2:8b` is 8 harmonics and the backlash,
//! `J2:b` the backlash alone.
//!
//! # The choice ([`choose`])
//! The postures are dealt into 5 folds (posture `p` of the training postures in fold `p mod K`);
//! each candidate's held-out error is the sum over folds of the errors of the fold's postures
//! predicted by the fit of the others, at its best ridge (a held-out posture beyond the others'
//! range of an axis with that axis's map tapered as the calibrated robot's: [`Linear::split`]).
//! First each joint alone, at each harmonic count, and each joint's backlash term alone (with
//! directions); then, from no map, these in the order of their own held-out error, each kept when
//! it lowers the held-out error by more than `MAP_ACCEPT` standard errors of the paired
//! per-posture differences (a one-sided test at about 0.6 %) and by 2 % of it: the choice keeps no
//! map on a robot without one. Then jointly: the first `k` joints of that order (`k` from 2)
//! together at each harmonic count up to the largest any of them chose alone, the one with the
//! least held-out error replacing the forward choice where it has less and lowers the error without
//! maps by the same rule (one joint at a time stops early where several joints' maps each gain a
//! little). The choice is made on the linearised fit (`linear`): exact to second order in the
//! parameters' change from the fit, a few nanometres on a calibrated robot.
//!
//! # The honest figure ([`nested`])
//! An outer cross-validation of 5 folds makes the whole choice on each outer fold's training
//! postures and predicts its held-out postures with it, beside the geometry alone on the same
//! split: the held-out gain of choosing maps by cross-validation. Inside outer fold `k` the
//! choice's inner folds are the other outer folds, each trained on the postures of neither: the two
//! outer folds of a pair share its split and each candidate's steps on it, so the `K` choices cost
//! `K (K - 1) / 2` splits, not `K^2` (with 3 outer folds or more). An outer fold's choice, whose
//! candidates are not reported, scores a candidate of the forward or the joint step one inner
//! fold after the other and drops it once its held-out error at every ridge reaches what it
//! must beat to be kept (`Inner::score_below`): the same choice, at a fraction of the
//! cost of the candidates that lose. Folds run in parallel (rayon),
//! the result independent of the thread count. [`nested_given`] scores the choices and ridges
//! another linearisation of the same postures made (a calibration's ladder chooses the maps once,
//! at its first gravity model): one refit per outer fold. Where the maps are fixed (or none), the
//! splits project the columns of these maps alone ([`Linear::restricted`]): the later rungs and
//! each outer fold's figure cost the columns they use, not the candidates'.
//!
//! Equations and sources: docs/model.md, section "Calibration", "Joint error maps".

mod inner;
pub(crate) mod linear;

pub(crate) use super::acceptance::lowers;
use super::acceptance::LEAST_GAIN;
pub use super::error_model::JointMaps;
pub use linear::{extended, Linear};

use inner::{folds, Inner, Pairs, Scored};
use rayon::prelude::*;
use stiffid_core::common::error::JobOption;
use stiffid_core::robot::error_map::MAX_HARMONICS;
use stiffid_core::{Error, Result};

/// Maps as documents name them: `J3:16,J5:8b` (a `b` for a backlash term; `J2:b` the backlash
/// alone), or `none`.
pub fn name(h: &JointMaps) -> String {
    let parts: Vec<String> = (0..6)
        .filter(|&j| h.has(j))
        .map(|j| {
            let n = h.harmonics[j];
            let b = if h.backlash[j] { "b" } else { "" };
            match n {
                0 => format!("J{}:b", j + 1),
                _ => format!("J{}:{n}{b}", j + 1),
            }
        })
        .collect();
    match parts.is_empty() {
        true => "none".into(),
        false => parts.join(","),
    }
}

/// The harmonic counts `--maps auto` tries per joint.
pub(crate) const HARMONICS: [usize; 4] = [4, 8, 16, 32];

/// The harmonics of a joint named without a count (`--maps J2`).
pub(crate) const DEFAULT_HARMONICS: usize = 16;

/// The ridges `mu` tried (dimensionless, per reading): up to 1, since from 50 postures a
/// joint's 32 harmonics may need a stronger hold than from 100.
pub(crate) const RIDGES: [f64; 11] = [
    1e-6, 1e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2, 1e-1, 3e-1, 1.0,
];

/// The folds of the inner and of the outer cross-validation.
pub(crate) const FOLDS: usize = 5;

/// The standard errors of the paired per-posture differences by which a carrier's error motion
/// order must lower the held-out error to be kept ([`super::motions`]).
pub(crate) const ACCEPT: f64 = 3.0;

/// The standard errors of the paired per-posture differences by which a joint's map must lower
/// the held-out error to be kept: fewer than `ACCEPT`, since the per-posture errors of a
/// campaign of 50 postures are heavy-tailed (a map that cut the inner held-out squared error of
/// the UR10's series C by a quarter stood 2.5 to 3 standard errors out); the choice still keeps
/// no map on a robot without one in 9 seeds of 10 or more from 50 postures (`maps_tests.rs`;
/// at 2 standard errors, in 34 of 40).
pub(crate) const MAP_ACCEPT: f64 = 2.5;

/// The fewest distinct postures with which `--maps auto` considers maps (below it, none): five
/// folds of at least six postures.
pub const MIN_POSTURES: usize = 30;

/// Which maps a calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Spec {
    /// Chosen by cross-validation with [`MIN_POSTURES`] postures or more, none below.
    #[default]
    Auto,
    /// None.
    None,
    /// These joints with these harmonics and backlash terms (the ridge chosen by
    /// cross-validation).
    Fixed(JointMaps),
}

impl Spec {
    /// Parses `auto`, `none` or a list of joints `J1,J3:16,J4:8b,J5:b` (a joint `J1`..`J6`,
    /// optionally `:H` harmonics, 1 to [`MAX_HARMONICS`], default 16, a `b` after them for a
    /// backlash term too, `:b` the backlash term alone).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::Maps`]) naming the part not understood.
    pub fn parse(text: &str) -> Result<Self> {
        let text = text.trim();
        match text {
            "auto" => return Ok(Spec::Auto),
            "none" => return Ok(Spec::None),
            _ => {}
        }
        let bad = |part: &str| {
            Error::InvalidOption {
            option: JobOption::Maps,
            message: format!(
                "expected auto, none or joints such as J1,J3:16,J4:8b,J5:b (J1 to J6, 1 to {MAX_HARMONICS} harmonics, b a backlash term), got {part:?}"
            ),
        }
        };
        // Digits only: `+1`, `01` or `1e1` are not a joint or a count.
        let number = |t: &str| {
            (!t.is_empty() && t.bytes().all(|b| b.is_ascii_digit()) && !t.starts_with('0'))
                .then(|| t.parse::<usize>().ok())
                .flatten()
        };
        let mut maps = JointMaps::NONE;
        for part in text.split(',') {
            let part = part.trim();
            let (joint, count) = part.split_once(':').unwrap_or((part, ""));
            let joint = (joint.strip_prefix(['J', 'j']))
                .and_then(number)
                .filter(|j| (1..=6).contains(j))
                .ok_or_else(|| bad(part))?;
            let (count, backlash) = match count.strip_suffix('b') {
                Some(c) => (c, true),
                None => (count, false),
            };
            let count = match (count, backlash) {
                ("", true) => 0,
                ("", false) if !part.contains(':') => DEFAULT_HARMONICS,
                (c, _) => number(c)
                    .filter(|h| (1..=MAX_HARMONICS).contains(h))
                    .ok_or_else(|| bad(part))?,
            };
            if maps.has(joint - 1) {
                return Err(Error::InvalidOption {
                    option: JobOption::Maps,
                    message: format!("J{joint} is given twice in {text:?}: give each joint once"),
                });
            }
            maps.harmonics[joint - 1] = count;
            maps.backlash[joint - 1] = backlash;
        }
        Ok(Spec::Fixed(maps))
    }

    /// The maps the linearised fit needs columns for: every joint at the largest of 4, 8, 16 or 32
    /// for [`Spec::Auto`], with a backlash term each where the readings carry `directions`; the
    /// fixed ones; none.
    pub fn candidates(self, directions: bool) -> JointMaps {
        match self {
            Spec::Auto => JointMaps {
                harmonics: [HARMONICS[HARMONICS.len() - 1]; 6],
                backlash: [directions; 6],
            },
            Spec::None => JointMaps::NONE,
            Spec::Fixed(h) => h,
        }
    }
}

/// One candidate the choice evaluated.
#[derive(Debug, Clone, PartialEq)]
pub struct Tried {
    /// Its maps and backlash terms.
    pub maps: JointMaps,
    /// Its best ridge.
    pub ridge: f64,
    /// Its held-out RMS error (inner cross-validation), m.
    pub rms: f64,
    /// Whether the choice kept it (a step of the forward selection that passed `ACCEPT`).
    pub kept: bool,
}

/// The maps chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// The harmonics of each joint's map (0 none) and its backlash terms.
    pub maps: JointMaps,
    /// The ridge.
    pub ridge: f64,
    /// The held-out RMS error of the choice (inner cross-validation: the figure it was tuned on), m.
    pub rms: f64,
    /// The held-out RMS error without maps on the same folds, m.
    pub none_rms: f64,
    /// Every candidate evaluated, in order.
    pub tried: Vec<Tried>,
}

/// The held-out gain of choosing maps by cross-validation (the outer folds).
#[derive(Debug, Clone, PartialEq)]
pub struct Nested {
    /// The outer folds.
    pub folds: usize,
    /// The held-out RMS error without maps, m.
    pub none_rms: f64,
    /// The held-out RMS error with the maps each outer fold chose on its training postures, m.
    pub rms: f64,
    /// The maps each outer fold chose.
    pub choices: Vec<JointMaps>,
    /// The ridge each outer fold chose with its maps (`mu`, `RIDGES`).
    pub ridges: Vec<f64>,
    /// Per held-out posture (the outer folds' in order: fold `k` holds the postures `i` with
    /// `i mod K = k`), the sum of its squared errors without maps, m^2.
    pub none_errors: Vec<f64>,
    /// The same with the maps each outer fold chose, m^2.
    pub errors: Vec<f64>,
}

/// Whether `candidate` lowers the held-out error of `current` by more than `MAP_ACCEPT`
/// standard errors of the paired per-posture differences and by
/// [`super::acceptance::LEAST_GAIN`] of it.
fn better(current: &Scored, candidate: &Scored) -> bool {
    lowers(
        (&current.errors, current.total),
        (&candidate.errors, candidate.total),
        MAP_ACCEPT,
    )
}

/// Chooses the maps of `spec` by cross-validation over the postures `postures` of `linear`
/// (module docs).
///
/// # Errors
/// [`Error::NotFinite`] when an SVD does not converge.
pub fn choose(linear: &Linear, postures: &[usize], spec: Spec) -> Result<Choice> {
    let narrow = narrowed(linear, spec);
    choose_on(
        &Inner::new(narrow.as_ref().unwrap_or(linear), postures)?,
        spec,
        false,
    )
}

/// `linear` with the columns of fixed maps alone, or none, for `spec` (`None` for
/// [`Spec::Auto`]): the splits project these alone.
fn narrowed(linear: &Linear, spec: Spec) -> Option<Linear> {
    match spec {
        Spec::Auto => None,
        Spec::None => Some(linear.restricted(&JointMaps::NONE)),
        Spec::Fixed(h) => Some(linear.restricted(&h)),
    }
}

/// [`choose`] on the inner cross-validation `inner`; with `prune`, a candidate of the forward or
/// the joint step is scored only until its folds show it cannot be kept
/// ([`Inner::score_below`]: the same choice and ridge, its `tried` without those candidates).
fn choose_on(inner: &Inner, spec: Spec, prune: bool) -> Result<Choice> {
    let none = inner.score(&JointMaps::NONE)?;
    let none_rms = inner.rms(&none);
    let mut tried = Vec::new();
    let mut record = |maps: JointMaps, s: &Scored, kept: bool| {
        tried.push(Tried {
            maps,
            ridge: s.ridge,
            rms: inner.rms(s),
            kept,
        })
    };
    let (mut chosen, mut current) = (JointMaps::NONE, none.clone());
    match spec {
        Spec::None => {}
        Spec::Fixed(h) => {
            let s = inner.score(&h)?;
            record(h, &s, true);
            (chosen, current) = (h, s);
        }
        Spec::Auto => {
            let mut alone = alone(inner, &mut record)?;
            alone.sort_by(|a, b| a.1.total_cmp(&b.1));
            let order: Vec<usize> = (alone.iter())
                .filter_map(|(m, _)| (0..6).find(|&j| m.harmonics[j] > 0))
                .collect();
            // Each joint's best harmonic count alone.
            let best: [usize; 6] = std::array::from_fn(|j| {
                alone.iter().map(|(m, _)| m.harmonics[j]).max().unwrap_or(0)
            });
            // Forward: the terms in that order, each kept when it lowers the error enough (by
            // `LEAST_GAIN` of it at least: `lowers`).
            for (term, _) in alone {
                let choice = chosen.union(&term);
                let bound = (1.0 - LEAST_GAIN) * current.total;
                let Some(s) = scored(inner, &choice, prune.then_some(bound))? else {
                    continue;
                };
                let kept = better(&current, &s);
                record(choice, &s, kept);
                if kept {
                    (chosen, current) = (choice, s);
                }
            }
            // Jointly: the first joints of that order together, at each harmonic count up to the
            // largest any of them chose alone (more harmonics than each joint's own best fit
            // the noise of every joint at once, at the cost of the widest candidates); the
            // best of these replaces the forward choice when its held-out error is lower and it
            // lowers the error without maps by the same rule.
            for k in 2..=order.len() {
                let largest = order[..k].iter().map(|&j| best[j]).max().unwrap_or(0);
                for &h in HARMONICS.iter().filter(|&&h| h <= largest) {
                    let mut set = JointMaps::NONE;
                    for &j in &order[..k] {
                        set.harmonics[j] = h;
                    }
                    let bound = current.total.min((1.0 - LEAST_GAIN) * none.total);
                    let Some(s) = scored(inner, &set, prune.then_some(bound))? else {
                        continue;
                    };
                    let kept = s.total < current.total && better(&none, &s);
                    record(set, &s, kept);
                    if kept {
                        (chosen, current) = (set, s);
                    }
                }
            }
        }
    }
    let rms = inner.rms(&current);
    Ok(Choice {
        maps: chosen,
        ridge: current.ridge,
        rms,
        none_rms,
        tried,
    })
}

/// The score of `choice` on `inner`: in full, or with a `bound` `None` where it reaches it
/// ([`Inner::score_below`]).
fn scored(inner: &Inner, choice: &JointMaps, bound: Option<f64>) -> Result<Option<Scored>> {
    match bound {
        None => inner.score(choice).map(Some),
        Some(b) => inner.score_below(choice, b),
    }
}

/// Each joint's map alone at its best of [`HARMONICS`], and each candidate backlash term alone
/// ([`Linear::candidates`]), with their held-out errors (the sums over the folds, m^2), each
/// evaluated candidate given to `record`.
fn alone(
    inner: &Inner,
    record: &mut impl FnMut(JointMaps, &Scored, bool),
) -> Result<Vec<(JointMaps, f64)>> {
    let mut alone = Vec::new();
    for joint in 0..6 {
        let mut best: Option<(JointMaps, f64)> = None;
        for &h in &HARMONICS {
            let mut choice = JointMaps::NONE;
            choice.harmonics[joint] = h;
            let s = inner.score(&choice)?;
            record(choice, &s, false);
            if best.as_ref().is_none_or(|(_, b)| s.total < *b) {
                best = Some((choice, s.total));
            }
        }
        alone.extend(best);
    }
    for joint in (0..6).filter(|&j| inner.linear.candidates.backlash[j]) {
        let mut choice = JointMaps::NONE;
        choice.backlash[joint] = true;
        let s = inner.score(&choice)?;
        record(choice, &s, false);
        alone.push((choice, s.total));
    }
    Ok(alone)
}

/// The held-out gain of [`choose`] by an outer cross-validation over `postures` (module docs).
///
/// # Errors
/// Those of [`choose`].
pub fn nested(linear: &Linear, postures: &[usize], spec: Spec) -> Result<Nested> {
    let narrow = narrowed(linear, spec);
    let pairs = Pairs::new(narrow.as_ref().unwrap_or(linear), postures)?;
    outer(linear, postures, |k, train| {
        let choice = match &pairs {
            // Each fold's `tried` is not reported: its candidates that cannot be kept are
            // scored only as far as it takes to show it.
            Some(pairs) => choose_on(&pairs.inner(k), spec, true)?,
            None => choose(linear, train, spec)?,
        };
        Ok((choice.maps, choice.ridge))
    })
}

/// [`nested`] with each outer fold's maps and ridge given: those `first` chose
/// ([`Nested::choices`], [`Nested::ridges`]: another linearisation of the same postures, a
/// calibration's first gravity model), each fold refitted with them on its training postures
/// and scored on its held-out ones: the held-out figure of a choice already made, at the cost of
/// one candidate per fold.
///
/// # Errors
/// [`Error::InvalidField`] (`choices`) unless `first` has one choice and one ridge per outer
/// fold; those of [`Linear::split`] and [`Linear::errors`].
pub fn nested_given(linear: &Linear, postures: &[usize], first: &Nested) -> Result<Nested> {
    let folds = FOLDS.min(postures.len());
    if first.choices.len() != folds || first.ridges.len() != folds {
        return Err(Error::InvalidField {
            field: "choices".into(),
            message: format!(
                "expected one choice of maps and one ridge per outer fold ({folds}), got {} and {}",
                first.choices.len(),
                first.ridges.len()
            ),
        });
    }
    outer(linear, postures, |k, _| {
        Ok((first.choices[k], first.ridges[k]))
    })
}

/// The outer cross-validation of [`nested`] over `postures`, each fold's maps and ridge given
/// by `chosen` (its index and training postures).
fn outer(
    linear: &Linear,
    postures: &[usize],
    chosen: impl Fn(usize, &[usize]) -> Result<(JointMaps, f64)> + Sync,
) -> Result<Nested> {
    let parts = folds(postures);
    let outer = (parts.par_iter().enumerate())
        .map(|(k, (train, test))| {
            let (maps, ridge) = chosen(k, train)?;
            let linear = linear.restricted(&maps);
            let split = linear.split(train, test)?;
            let n: usize = train.iter().map(|&p| linear.rows[p].len() / 3).sum();
            let with = linear.errors(&split, &maps, &[ridge * n as f64])?;
            let none = linear.errors(&split, &JointMaps::NONE, &[0.0])?;
            let first = |mut e: Vec<Vec<f64>>| e.swap_remove(0);
            Ok((first(with), first(none), maps, ridge))
        })
        .collect::<Result<Vec<_>>>()?;
    let readings: usize = postures.iter().map(|&p| linear.rows[p].len() / 3).sum();
    let rms = |e: &[f64]| (e.iter().sum::<f64>() / readings.max(1) as f64).sqrt();
    let errors: Vec<f64> = outer.iter().flat_map(|o| o.0.clone()).collect();
    let none_errors: Vec<f64> = outer.iter().flat_map(|o| o.1.clone()).collect();
    Ok(Nested {
        folds: parts.len(),
        rms: rms(&errors),
        none_rms: rms(&none_errors),
        choices: outer.iter().map(|o| o.2).collect(),
        ridges: outer.iter().map(|o| o.3).collect(),
        none_errors,
        errors,
    })
}

#[cfg(test)]
mod inner_tests;
