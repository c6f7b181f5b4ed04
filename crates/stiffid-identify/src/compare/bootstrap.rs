//! The posture bootstrap of the model choice: how the chosen model and its stiffness vary when the
//! data vary (Efron, Tibshirani, "An Introduction to the Bootstrap", 1993, ch. 6 and 13).
//!
//! Each resample draws as many postures as the data hold, uniformly with replacement (a posture's
//! measurements stay together), and redoes the whole comparison on it exactly as on the data
//! ([`super::compare`] without the nested estimate): the forward selection and the
//! one-standard-error recommendation. A posture drawn more than once is a posture measured
//! again: its copies keep its label, so the leave-one-posture-out error holds them out together
//! (leave one *distinct* posture out) and counts the posture once in the held-out mean square,
//! as a measurement file with repeated measurements of one posture is treated. Holding one copy
//! out while another stays in the fit would predict it from itself and favour larger models.
//!
//! Resample `b` (`0..resamples`) draws with ChaCha8 seeded by the seed on stream `b`, and the
//! resamples run in parallel: the same seed gives the same result whatever the thread count. A
//! resample whose data cannot identify the recommended model (too few distinct postures, or
//! postures that leave a parameter unidentified) is counted and left out of the shares and
//! spreads.
//!
//! What it is: the spread of each stiffness over the models the data would choose, the selection
//! included. What it is not: a confidence interval conditional on one model (those are the
//! recommended fit's intervals), nor a correction of a model's bias (a compliance no candidate
//! expresses biases every resample alike).

use super::{compare, Comparison};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use stiffid_core::common::progress::{Progress, Tally};
use stiffid_core::observation::Measurement;
use stiffid_core::JobOption;
use stiffid_core::{Error, Result, Setup};

/// The resampling asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Resampling {
    /// The number of resamples, 1 to [`stiffid_core::common::limits::MAX_BOOTSTRAP`].
    pub resamples: usize,
    /// The seed of the draws.
    pub seed: u64,
}

impl Resampling {
    /// Checks the number of resamples.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] ([`JobOption::Bootstrap`]) outside 1 to
    /// [`stiffid_core::common::limits::MAX_BOOTSTRAP`].
    pub fn check(&self) -> Result<()> {
        let max = stiffid_core::common::limits::MAX_BOOTSTRAP;
        if (1..=max).contains(&(self.resamples as u64)) {
            return Ok(());
        }
        Err(Error::InvalidOption {
            option: JobOption::Bootstrap,
            message: format!("{} resamples: expected 1 to {max}", self.resamples),
        })
    }
}

/// One parameter's share of the resamples and the spread of its value in those that chose it.
#[derive(Debug, Clone, PartialEq)]
pub struct Spread {
    /// The parameter's index in [`Comparison::parameters`].
    pub parameter: usize,
    /// The usable resamples whose recommended model holds it.
    pub chosen: usize,
    /// The median, 2.5% and 97.5% percentiles ([`percentile`]) of its value over those
    /// resamples, SI: the stiffness (Nm/rad, N/m), or for a lost motion and a load-dependent
    /// compliance the parameter itself (rad, rad/(Nm)^2).
    pub median: f64,
    /// The 2.5% percentile.
    pub lower: f64,
    /// The 97.5% percentile.
    pub upper: f64,
}

/// One resample's recommended model: its parameters (indices in [`Comparison::parameters`],
/// ascending) with their SI values ([`Spread::median`]).
pub(crate) type Chosen = Vec<(usize, f64)>;

/// A model one resample's data support (`super::supported`): its parameters (indices in
/// [`Comparison::parameters`], the setup's model's first, then the springs in the order the
/// selection added them) and the compliance-side value of each, SI (rad/Nm, m/N; a lost motion
/// in rad or m, a load-dependent compliance in rad/Nm^2).
pub(crate) type Supported = (Vec<usize>, Vec<f64>);

/// The result of [`bootstrap`].
#[derive(Debug, Clone, PartialEq)]
pub struct Bootstrap {
    /// The resampling.
    pub resampling: Resampling,
    /// Each resample's recommended model, by resample index; `None` when its data cannot
    /// identify it (module docs).
    pub models: Vec<Option<Chosen>>,
    /// Each resample's supported models, by resample index; empty when its data
    /// cannot identify its recommended model.
    pub supported: Vec<Vec<Supported>>,
    /// The resamples whose data cannot identify their recommended model (module docs).
    pub unidentified: usize,
    /// The usable resamples whose recommended model is exactly the data's (the same parameters).
    pub recommended: usize,
    /// Every parameter chosen in at least one usable resample, in [`Comparison::parameters`]
    /// order (the setup's model's first).
    pub parameters: Vec<Spread>,
}

impl Bootstrap {
    /// The usable resamples: all but the unidentified.
    pub fn usable(&self) -> usize {
        self.resampling.resamples - self.unidentified
    }
}

/// The `p` percentile (`0..=1`) of `sorted` (ascending, not empty) by linear interpolation
/// between order statistics: `x[i] + f (x[i+1] - x[i])` with `i + f = p (n - 1)` (Hyndman, Fan,
/// "Sample quantiles in statistical packages", Am. Stat. 50, 1996, definition 7; NumPy's
/// default).
///
/// # Panics
/// If `sorted` is empty.
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    let at = p * (sorted.len() - 1) as f64;
    let i = at.floor() as usize;
    let f = at - i as f64;
    match sorted.get(i + 1) {
        Some(next) if f > 0.0 => sorted[i] + f * (next - sorted[i]),
        _ => sorted[i],
    }
}

/// The recommended model of `c` ([`Chosen`]); `None` when its data do not identify it.
fn chosen(c: &Comparison) -> Option<Chosen> {
    let row = &c.models[c.recommended];
    if !row.identified {
        return None;
    }
    let mut out: Vec<(usize, f64)> = row
        .parameter_indices
        .iter()
        .zip(&row.stiffness)
        .map(|(&j, &k)| match c.parameters[j].unit.is_stiffness() {
            true => (j, k),
            false => (j, 1.0 / k),
        })
        .collect();
    out.sort_by_key(|x| x.0);
    Some(out)
}

/// The models `c`'s data support ([`Supported`]); none when its data do not identify its
/// recommended model.
fn supported(c: &Comparison) -> Vec<Supported> {
    if !c.models[c.recommended].identified {
        return Vec::new();
    }
    (super::supported(&c.models).into_iter())
        .map(|i| {
            let row = &c.models[i];
            let h = row.stiffness.iter().map(|k| 1.0 / k).collect();
            (row.parameter_indices.clone(), h)
        })
        .collect()
}

/// The measurements of resample `b` (module docs): postures drawn with replacement, each with
/// all its measurements and its label.
fn resample(postures: &[Vec<&Measurement>], seed: u64, b: usize) -> Vec<Measurement> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(b as u64);
    let n = postures.len();
    (0..n)
        .flat_map(|_| postures[rng.random_range(0..n)].iter().map(|&m| m.clone()))
        .collect()
}

/// The posture bootstrap (module docs) of the comparison `data` made of `measurements` over
/// `candidates` from `setup`'s model. `progress` hears one stage, `bootstrap resamples`, one
/// unit per resample.
///
/// # Errors
/// Those of [`Resampling::check`].
pub fn bootstrap(
    setup: &Setup,
    measurements: &[Measurement],
    candidates: &[stiffid_core::model::Spring],
    data: &Comparison,
    resampling: Resampling,
    progress: &dyn Progress,
) -> Result<Bootstrap> {
    resampling.check()?;
    let mut labels: Vec<usize> = measurements.iter().map(|m| m.posture).collect();
    labels.sort_unstable();
    labels.dedup();
    let mut postures: Vec<Vec<&Measurement>> = vec![Vec::new(); labels.len()];
    for m in measurements {
        let p = labels
            .binary_search(&m.posture)
            .expect("a label of the data");
        postures[p].push(m);
    }
    progress.begin("bootstrap resamples", resampling.resamples);
    let tally = Tally::new(progress);
    let (models, supported): (Vec<Option<Chosen>>, Vec<Vec<Supported>>) = (0..resampling.resamples)
        .into_par_iter()
        .map(|b| {
            let data = resample(&postures, resampling.seed, b);
            let c = compare(setup, &data, candidates, false).ok();
            tally.add(1);
            match c {
                Some(c) => (chosen(&c), supported(&c)),
                None => (None, Vec::new()),
            }
        })
        .unzip();
    progress.end();
    let usable: Vec<&Chosen> = models.iter().flatten().collect();
    let mut exact: Vec<usize> = data.models[data.recommended].parameter_indices.clone();
    exact.sort_unstable();
    let recommended = usable
        .iter()
        .filter(|r| r.iter().map(|x| x.0).eq(exact.iter().copied()))
        .count();
    let parameters = (0..data.parameters.len())
        .filter_map(|j| spread(j, &usable))
        .collect();
    Ok(Bootstrap {
        resampling,
        unidentified: models.len() - usable.len(),
        recommended,
        parameters,
        models,
        supported,
    })
}

/// Parameter `j`'s [`Spread`] over the usable resamples that chose it; `None` if none did.
fn spread(j: usize, usable: &[&Chosen]) -> Option<Spread> {
    let mut values: Vec<f64> = usable
        .iter()
        .filter_map(|r| r.iter().find(|x| x.0 == j).map(|x| x.1))
        .collect();
    if values.is_empty() {
        return None;
    }
    values.sort_by(f64::total_cmp);
    Some(Spread {
        parameter: j,
        chosen: values.len(),
        median: percentile(&values, 0.5),
        lower: percentile(&values, 0.025),
        upper: percentile(&values, 0.975),
    })
}
