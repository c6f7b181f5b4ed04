//! The model a calibration fits when it is not told (`--gravity auto`, `--maps auto`): a ladder
//! of nested models climbed by a cross-validation that holds out groups of postures.
//!
//! # The rungs
//! In order of complexity, each gravity model (the rigid robot, the arm's three terms (skipped,
//! saying why, on a robot that is not an anthropomorphic arm), the lumped bodies, the lumped links,
//! the known masses where the robot gives them) without joint error maps and then with the maps of
//! `--maps` (chosen by [`crate::calibration::maps`] inside every training set; where `auto` keeps
//! no map on every posture, the rungs with maps are the ones without and are skipped saying so). A
//! named `--gravity` other than `none` is a ladder of the geometry and that model, judged as the
//! ladder judges its rung and refused where it would be skipped ([`super::named`]; not with
//! `--update`, whose model is the calibrated robot's: a ladder of one); `--maps none` or fixed
//! maps is one maps variant; a ladder of one rung is not climbed.
//!
//! # The held-out figure
//! Each rung is fitted to every reading (its gravity terms bounded by
//! [`crate::calibration::fit::GravityPrior`]); a rung whose fit does not converge, whose scaled
//! Jacobian's condition exceeds 1e6 or that deflects a joint beyond the physically possible
//! ([`super::named::beyond_sag`]) is skipped (the simpler model kept), and so is a rung that
//! extrapolates: one whose expected error where the robot is used ([`super::region`]: the
//! joint-space hull of the postures of the campaign and of the setup) exceeds that of the geometry
//! with the same maps variant by more than the held-out figures resolve, the expected error being
//! the rung's own held-out error (below: with maps, the error with its maps) and the RMS standard
//! deviation of its gravity model's predictions over that region (`postures_sds`, where the readings
//! leave the terms to their prior; with maps at the noise the maps leave, the fit without maps'
//! scaled by the ratio of the two held-out errors: `crate::calibration::spread`) in quadrature: bias and
//! variance; its square may exceed the geometry's by one standard error of the difference of their
//! held-out mean squared errors (the paired per-posture differences), as the choice below allows: a
//! difference the groups cannot resolve does not turn a model down. A gravity model that
//! extrapolates without maps is judged again with them: what the maps hold (an axis's periodic
//! error) no longer biases its held-out error. The groups held out among the fitted postures cannot
//! show what the spread shows; postures the robot never takes do not turn a model down. The
//! postures are dealt into 5 groups (posture `i` in group `i mod K`); each group is predicted by
//! the rung refitted without it (linearised at the rung's fit, as the maps' choice:
//! [`crate::calibration::maps::nested`], the maps chosen on each training set at the first gravity
//! model's fit and kept, with their ridges, for the others, as the maps chosen on every posture
//! there are: [`crate::calibration::maps::nested_given`]), which gives every held-out posture its
//! squared error under every rung, paired.
//!
//! # The choice (one standard error)
//! The rung with the least held-out error is the best; the job fits the simplest rung whose
//! held-out squared error exceeds the best's by at most one standard error of their paired
//! per-posture differences and by no more than any simpler rung's: a model is never chosen
//! over a simpler one that predicts the held-out postures better. With fewer than
//! `MIN_POSTURES` (10) distinct postures the ladder is not climbed and its first rung is fitted.

use super::maps::{assess, assess_given, keeps_none, Assessed};
use super::region::Region;
use super::WEAK_CONDITION;
use crate::calibration::error_model::Observation;
use crate::calibration::fit::{stop_warning, Fit, Options};
use crate::calibration::gravity::Gravity;
use crate::calibration::maps::{Spec, FOLDS};
use crate::calibration::spread::postures_sds;
use crate::calibration::{motions, ErrorModel, Estimate};
use stiffid_core::common::choice::Choice;
use stiffid_core::common::limits::JointBox;
use stiffid_core::Result;

/// The gravity models of `--gravity auto`, in order of complexity ([`Gravity::Masses`] only on a
/// robot with link masses).
pub(crate) const GRAVITY_RUNGS: [Gravity; 5] = [
    Gravity::None,
    Gravity::Arm,
    Gravity::Lumped,
    Gravity::LumpedLinks,
    Gravity::Masses,
];

/// The fewest distinct postures with which the ladder is climbed (10): two per fold.
pub(crate) const MIN_POSTURES: usize = 2 * FOLDS;

/// Which gravity terms a calibration fits: chosen by the ladder, or given.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GravitySpec {
    /// Chosen by the ladder (module docs).
    #[default]
    Auto,
    /// These.
    Fixed(Gravity),
}

impl Choice for GravitySpec {
    const FIELD: &'static str = "gravity";
    const ALL: &'static [Self] = &[
        GravitySpec::Auto,
        GravitySpec::Fixed(Gravity::None),
        GravitySpec::Fixed(Gravity::Arm),
        GravitySpec::Fixed(Gravity::Masses),
        GravitySpec::Fixed(Gravity::Lumped),
        GravitySpec::Fixed(Gravity::LumpedLinks),
    ];
    fn name(self) -> &'static str {
        match self {
            GravitySpec::Auto => "auto",
            GravitySpec::Fixed(g) => g.name(),
        }
    }
    fn help(self) -> &'static str {
        match self {
            GravitySpec::Auto => {
                "Chosen with the maps by a cross-validation holding out groups of postures"
            }
            GravitySpec::Fixed(g) => g.help(),
        }
    }
}

stiffid_core::common::choice::by_name!(GravitySpec);

impl GravitySpec {
    /// The gravity models to try on a robot with (`masses`) or without link masses.
    pub fn rungs(self, masses: bool) -> Vec<Gravity> {
        match self {
            GravitySpec::Fixed(g) => vec![g],
            GravitySpec::Auto => (GRAVITY_RUNGS.iter().copied())
                .filter(|&g| masses || g != Gravity::Masses)
                .collect(),
        }
    }
}

/// One rung of the ladder.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    /// Its gravity terms.
    pub gravity: Gravity,
    /// Whether it fits the joint error maps of `--maps` (chosen inside each training set).
    pub maps: bool,
    /// Its held-out RMS error over the groups, m; `None` when not scored (a skipped rung keeps
    /// it when it was scored before it was found to extrapolate).
    pub rms: Option<f64>,
    /// Why it was skipped (a fit that does not converge, is ill-conditioned, fails or
    /// extrapolates).
    pub skipped: Option<String>,
    /// The RMS standard deviation of its gravity model's predictions over the region where the
    /// robot is used ([`Ladder::region`], `postures_sds`; with maps at the noise they leave), m;
    /// `None` when not computed.
    pub spread: Option<f64>,
    /// Per held-out posture (the groups' in order), its sum of squared errors, m^2; empty when
    /// not scored.
    pub errors: Vec<f64>,
}

/// The ladder climbed.
#[derive(Debug, Clone, PartialEq)]
pub struct Ladder {
    /// The groups of postures held out in turn.
    pub folds: usize,
    /// The rungs, simplest first.
    pub rungs: Vec<Rung>,
    /// The rung chosen (an index of `rungs`).
    pub chosen: usize,
    /// The box of the axis angles of the region where the robot is used
    /// ([`super::region::Region::bounds`]), rad: the region over which the rungs' spread is
    /// judged lies within it.
    pub region: JointBox,
}

/// The rung chosen among `rungs` (simplest first) by the one-standard-error rule (module docs);
/// the first when none was scored.
pub fn choose(rungs: &[Rung]) -> usize {
    let total = |r: &Rung| r.errors.iter().sum::<f64>();
    let scored: Vec<usize> = (0..rungs.len())
        .filter(|&i| rungs[i].skipped.is_none() && !rungs[i].errors.is_empty())
        .collect();
    let Some(&best) = scored
        .iter()
        .min_by(|&&a, &&b| total(&rungs[a]).total_cmp(&total(&rungs[b])))
    else {
        return 0;
    };
    let within = |i: usize| {
        let d: Vec<f64> = (rungs[i].errors.iter().zip(&rungs[best].errors))
            .map(|(a, b)| a - b)
            .collect();
        let n = d.len() as f64;
        let mean = d.iter().sum::<f64>() / n;
        let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
        mean <= (var / n).sqrt()
    };
    let mut simplest = f64::INFINITY;
    for &i in &scored {
        let t = total(&rungs[i]);
        if within(i) && t <= simplest {
            return i;
        }
        simplest = simplest.min(t);
    }
    best
}

/// One gravity model fitted to every reading.
pub struct Fitted {
    /// The error model (with its error motions and loads).
    pub model: ErrorModel,
    /// The fit's start.
    pub start: Estimate,
    /// The fit.
    pub fit: Fit,
    /// With external axes: the error motions' choice.
    pub error_motions: Option<motions::Choice>,
}

/// What the ladder chose: the rung's fit, its maps assessed and whether they are kept (or why
/// not), and the ladder (`None` for a ladder of one rung).
pub struct Climbed {
    /// The chosen gravity model's fit.
    pub fitted: Fitted,
    /// Its maps assessed.
    pub assessed: Assessed,
    /// Whether the maps are kept, or why not.
    pub keep: std::result::Result<(), String>,
    /// The ladder.
    pub ladder: Option<Ladder>,
}

/// Climbs the ladder of `gravity` and `maps` (module docs), fitting each gravity model with
/// `fit` to `obs`, after `check` of the first model's fit (what refuses readings before any
/// choice is fitted).
///
/// # Errors
/// Those of `fit`, `check` and `assess` for the first gravity model (a later one that fails is
/// skipped).
pub fn climb(
    (gravity, maps): (GravitySpec, Spec),
    (masses, judge_named): (bool, bool),
    (obs, region): (&[Observation], &Region),
    options: &Options,
    (fit, check): (
        impl Fn(Gravity) -> Result<Fitted>,
        impl Fn(&Fitted) -> Result<()>,
    ),
) -> Result<Climbed> {
    let variants: &[bool] = match maps {
        Spec::Auto => &[false, true],
        Spec::None => &[false],
        Spec::Fixed(_) => &[true],
    };
    let mut postures: Vec<usize> = obs.iter().map(|o| o.posture).collect();
    postures.sort_unstable();
    postures.dedup();
    // A named gravity model judged as its rung, beside the geometry (module docs).
    let named = match gravity {
        GravitySpec::Fixed(g) if judge_named && g != Gravity::None => {
            Some(g).filter(|_| postures.len() >= MIN_POSTURES)
        }
        _ => None,
    };
    let gravities = match named {
        Some(g) => vec![Gravity::None, g],
        None => gravity.rungs(masses),
    };
    let climbed = gravities.len() * variants.len() > 1 && postures.len() >= MIN_POSTURES;
    let first = fit(gravities[0])?;
    check(&first)?;
    let assessed = assess(maps, (&first.model, &first.fit), obs, options, climbed)?;
    if !climbed {
        return Ok(unclimbed(
            (first, assessed),
            (&gravities, variants),
            postures.len(),
            region,
        ));
    }
    // The maps chosen for the first gravity model, on every posture and in each outer fold
    // (with their ridges), kept for the others.
    let mut later: Vec<std::result::Result<(Fitted, Assessed), String>> = Vec::new();
    for &g in &gravities[1..] {
        let tried = fit(g).and_then(|f| {
            let a = assess_given((&f.model, &f.fit), obs, options, &assessed)?;
            Ok((f, a))
        });
        // A named model that cannot be fitted at all (a robot without link masses for
        // `masses`) is refused for that reason, not as one the postures leave undetermined.
        let tried = match (tried, named) {
            (Err(e), Some(_)) => return Err(e),
            (tried, _) => tried.map_err(|e| e.to_string()),
        };
        later.push(tried.and_then(|(f, a)| {
            judged(&f, named.is_some())?;
            Ok((f, a))
        }));
    }
    let kept_none = keeps_none(&assessed.maps);
    let mut fits = vec![Ok((first, assessed))];
    fits.extend(later);
    // The rungs without maps first, then with them: the maps are the larger family.
    let order: Vec<(usize, bool)> = (variants.iter())
        .flat_map(|&v| (0..gravities.len()).map(move |g| (g, v)))
        .collect();
    let mut rungs: Vec<Rung> = (order.iter())
        .map(|&(g, v)| rung(gravities[g], v, &fits[g]))
        .collect();
    diverged(&mut rungs, &order);
    let like = obs.iter().find(|o| !o.table).unwrap_or(&obs[0]);
    spread(&mut rungs, &order, &fits, (like, region));
    if named.is_none() {
        extrapolating(&mut rungs, &order);
    }
    let chosen = match named {
        None => choose(&rungs),
        Some(named) => named_chosen(&rungs, named).map_err(|why| {
            let fitted =
                (fits.get(1).and_then(|f| f.as_ref().ok())).map(|(f, _)| (&f.model, &f.fit));
            super::named::refusal(named, &why, fitted, options)
        })?,
    };
    let (g, with_maps) = order[chosen];
    // Where `auto` keeps no map, the maps' choice says so, not the ladder.
    let why = (!with_maps && !kept_none).then(|| {
        let none = rungs[chosen].rms.unwrap_or(f64::NAN) * 1e3;
        format!("the ladder chose the model without maps ({none:.4} mm held out)")
    });
    let Ok((fitted, assessed)) = fits.swap_remove(g) else {
        unreachable!("a skipped rung is never chosen");
    };
    Ok(Climbed {
        fitted,
        assessed,
        keep: why.map_or(Ok(()), Err),
        // A named model's ladder is not reported: the model was given.
        ladder: named.is_none().then_some(Ladder {
            folds: FOLDS.min(postures.len()),
            rungs,
            chosen,
            region: region.bounds,
        }),
    })
}

/// The rung fitted for the named gravity model `gravity` among `rungs` (the geometry's and its,
/// without and with maps), by the ladder's rule among its own rungs alone; `Err` with the
/// reasons its rungs were skipped when every one was.
fn named_chosen(rungs: &[Rung], gravity: Gravity) -> std::result::Result<usize, String> {
    let own: Vec<Rung> = (rungs.iter())
        .map(|r| match r.gravity == gravity {
            true => r.clone(),
            false => Rung {
                skipped: Some("not the named model".into()),
                ..r.clone()
            },
        })
        .collect();
    let i = choose(&own);
    match own[i].gravity == gravity && own[i].skipped.is_none() && !own[i].errors.is_empty() {
        true => Ok(i),
        false => Err((rungs.iter())
            .filter(|r| r.gravity == gravity)
            .filter_map(|r| r.skipped.clone())
            .collect::<Vec<_>>()
            .join("; with maps: ")),
    }
}

/// Sets each rung's spread over the `region` (`postures_sds` for a reading `like`) from its
/// gravity model's fit of `fits` (`order` as [`extrapolating`]'s): a rung without maps at its fit's
/// noise, a rung with maps at the noise its maps leave, the fit's scaled by the ratio of the
/// rung's held-out RMS to its gravity model's without maps (at most 1; 1 where either is not
/// scored): the fit without maps counts what the maps hold as noise, and with them the readings
/// determine the terms as much better (`crate::calibration::spread`, *At another noise*).
fn spread<A>(
    rungs: &mut [Rung],
    order: &[(usize, bool)],
    fits: &[std::result::Result<(Fitted, A), String>],
    (like, region): (&Observation, &Region),
) {
    let scale = |i: usize| -> f64 {
        let (g, maps) = order[i];
        let without = (maps)
            .then(|| order.iter().position(|&o| o == (g, false)))
            .flatten();
        match (rungs[i].rms, without.and_then(|w| rungs[w].rms)) {
            (Some(with), Some(without)) if without > 0.0 => (with / without).min(1.0),
            _ => 1.0,
        }
    };
    let scales: Vec<f64> = (0..order.len()).map(scale).collect();
    for (g, fit) in fits.iter().enumerate() {
        let Ok((f, _)) = fit else {
            continue;
        };
        let mine: Vec<usize> = (0..order.len()).filter(|&i| order[i].0 == g).collect();
        let wanted: Vec<f64> = mine.iter().map(|&i| scales[i]).collect();
        let Ok(sds) = postures_sds(&f.model, &f.fit, like, &region.postures, &wanted) else {
            continue;
        };
        for (&i, sd) in mine.iter().zip(sds) {
            rungs[i].spread = Some(sd);
        }
    }
}

/// Skips the rungs (`order`: each one's gravity model's index and whether it fits maps) that
/// extrapolate: whose expected squared error where the robot is used, its own held-out error
/// and its gravity model's spread there in quadrature, exceeds that of the geometry with the
/// same maps variant by more than one standard error of their held-out difference (module docs).
pub(super) fn extrapolating(rungs: &mut [Rung], order: &[(usize, bool)]) {
    let expected = |r: &Rung| Some(r.rms?.hypot(r.spread?));
    let worse: Vec<Option<(f64, f64)>> = (order.iter().enumerate())
        .map(|(i, &(g, maps))| {
            let base = &rungs[(g > 0).then(|| order.iter().position(|&o| o == (0, maps)))??];
            let (e0, e) = (expected(base)?, expected(&rungs[i])?);
            (e * e > e0 * e0 + resolution(base, &rungs[i])).then_some((e, e0))
        })
        .collect();
    for (r, worse) in rungs.iter_mut().zip(worse) {
        let Some((e, e0)) = worse else {
            continue;
        };
        r.skipped = Some(format!(
            "it extrapolates: its predictions over the region where the robot is used spread by {:.3} mm, and with its held-out error it is expected {:.3} mm off there against {:.3} mm for the geometry{}, beyond what the held-out figures resolve (the postures leave its gravity terms to their bound)",
            r.spread.unwrap_or(f64::NAN) * 1e3,
            e * 1e3,
            e0 * 1e3,
            if r.maps { " with maps" } else { "" }
        ));
    }
}

/// Skips the rungs (`order` as [`extrapolating`]'s) whose held-out RMS over the groups exceeds
/// [`super::diverged::DIVERGED`] times that of the geometry with the same maps variant: a group's
/// fit without its postures diverged (undetermined along some direction), and its figure is no
/// robot's error. Their figure is not kept (a figure of metres is not a result).
pub(super) fn diverged(rungs: &mut [Rung], order: &[(usize, bool)]) {
    let limit = super::diverged::DIVERGED;
    let base: Vec<Option<f64>> = (order.iter())
        .map(|&(_, maps)| {
            let i = order.iter().position(|&o| o == (0, maps))?;
            rungs[i].rms.filter(|_| rungs[i].skipped.is_none())
        })
        .collect();
    for (r, base) in rungs.iter_mut().zip(base) {
        let (Some(rms), Some(base)) = (r.rms, base) else {
            continue;
        };
        if rms > limit * base || !rms.is_finite() {
            r.skipped = Some(format!(
                "its held-out error diverged: more than {limit:.0} times the geometry's{} over the groups ({:.4} mm), a group's fit without its postures undetermined along some direction",
                if r.maps { " with maps" } else { "" },
                base * 1e3
            ));
            r.rms = None;
            r.errors.clear();
        }
    }
}

/// One standard error of the difference of the held-out mean squared errors (per reading, m^2)
/// of `a` and `b` over their paired per-posture errors; 0 when either is not scored.
fn resolution(a: &Rung, b: &Rung) -> f64 {
    let n = a.errors.len();
    let total: f64 = a.errors.iter().sum();
    let Some(rms) = a.rms.filter(|&r| r > 0.0 && n >= 2 && b.errors.len() == n) else {
        return 0.0;
    };
    let readings = total / (rms * rms);
    let d: Vec<f64> = (a.errors.iter().zip(&b.errors))
        .map(|(x, y)| x - y)
        .collect();
    let mean = d.iter().sum::<f64>() / n as f64;
    let var = d.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    (n as f64 * var).sqrt() / readings
}

/// The ladder of one rung, or not climbed for too few postures: the first gravity model's fit
/// (`first`, its maps assessed) of `gravities` and the maps `variants`, `postures` distinct.
fn unclimbed(
    (first, assessed): (Fitted, Assessed),
    (gravities, variants): (&[Gravity], &[bool]),
    postures: usize,
    region: &Region,
) -> Climbed {
    let ladder = (gravities.len() * variants.len() > 1).then(|| Ladder {
        folds: 0,
        rungs: vec![unscored(gravities[0], variants[0], None)],
        chosen: 0,
        region: region.bounds,
    });
    let keep = match ladder {
        Some(_) => Err(format!(
            "{postures} distinct postures, fewer than the {MIN_POSTURES} with which the model is chosen"
        )),
        None => Ok(()),
    };
    Climbed {
        fitted: first,
        assessed,
        keep: keep.and(match variants[0] {
            true => Ok(()),
            false => Err("--maps none".into()),
        }),
        ladder,
    }
}

/// `Err` why a gravity model's fit is not a rung: its terms deflect a joint beyond the physically
/// possible ([`super::named::beyond_sag`]); unless it is a `named` model, its fit did not converge
/// or its scaled Jacobian's condition exceeds [`WEAK_CONDITION`].
fn judged(fitted: &Fitted, named: bool) -> std::result::Result<(), String> {
    if let Some(why) = super::named::beyond_sag(&fitted.model, &fitted.fit.estimate.values) {
        return Err(why);
    }
    let fit = &fitted.fit;
    if named {
        return Ok(());
    }
    if let Some(w) = stop_warning(fit.stop, fit.iterations) {
        return Err(w.message);
    }
    let condition = fit.identifiability.condition;
    match condition > WEAK_CONDITION {
        true => Err(format!(
            "the condition number of its scaled Jacobian is {condition:.3e}, above {WEAK_CONDITION:.0e}"
        )),
        false => Ok(()),
    }
}

/// The rung of gravity `gravity` with (`maps`) or without the maps, from its fit and
/// assessment (or why it has none).
fn rung(
    gravity: Gravity,
    maps: bool,
    fitted: &std::result::Result<(Fitted, Assessed), String>,
) -> Rung {
    let assessed = match fitted {
        Err(e) => return unscored(gravity, maps, Some(e.clone())),
        Ok((_, a)) => a,
    };
    let Some(nested) = &assessed.nested else {
        return unscored(gravity, maps, Some("not scored".into()));
    };
    match (maps, &assessed.maps.skipped) {
        (true, Some(why)) => unscored(gravity, maps, Some(format!("no map considered: {why}"))),
        (true, None) if keeps_none(&assessed.maps) => unscored(
            gravity,
            maps,
            Some("the maps' choice on every posture keeps none: the model without maps".into()),
        ),
        (true, None) => Rung {
            gravity,
            maps,
            rms: Some(nested.rms),
            skipped: None,
            spread: None,
            errors: nested.errors.clone(),
        },
        (false, _) => Rung {
            gravity,
            maps,
            rms: Some(nested.none_rms),
            skipped: None,
            spread: None,
            errors: nested.none_errors.clone(),
        },
    }
}

/// A rung not scored.
fn unscored(gravity: Gravity, maps: bool, skipped: Option<String>) -> Rung {
    Rung {
        gravity,
        maps,
        rms: None,
        skipped,
        spread: None,
        errors: Vec::new(),
    }
}
