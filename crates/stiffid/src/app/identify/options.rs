//! The options of the identify job as a user sets them, checked together once here, so that the
//! command and Python refuse the same combinations with the same error
//! ([`Error::OptionCombination`]).

use super::{Fit, Folds};
use stiffid_core::{Error, JobOption, Result};
use stiffid_identify::compare::Resampling;
use stiffid_identify::Loss;

/// The options of `stiffid identify` and of Python's `identify`, as set by the user: the fit,
/// the cross-validation, the offsets and the model comparison. [`Options::default`] is a
/// least-squares fit of the setup's model.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    /// Down-weight outliers by iteratively reweighted least squares with this loss.
    pub robust: Option<Loss>,
    /// Bound every compliance at `>= 0` (non-negative least squares).
    pub nonnegative: bool,
    /// Cross-validate over postures, one posture out (or [`Options::folds`] folds).
    pub cross_validate: bool,
    /// The number of cross-validation folds, 2 to the number of postures (implies
    /// cross-validation).
    pub folds: Option<usize>,
    /// Fit an offset per posture and measuring point beside the compliances
    /// ([`stiffid_identify::offsets`]; least squares of the six drive springs, without
    /// cross-validation).
    pub offsets: bool,
    /// Choose the model by the data: forward selection of candidate springs
    /// ([`stiffid_identify::compare`]).
    pub compare_models: bool,
    /// With `compare_models`, the candidates by name or family; `None` for all of them.
    pub candidates: Option<Vec<String>>,
    /// With `compare_models`, the number of posture bootstrap resamples.
    pub bootstrap: Option<usize>,
    /// With `bootstrap`, the seed of its draws (default 1).
    pub seed: Option<u64>,
}

/// What the options ask for, once checked.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Plan {
    /// One fit of the setup's model.
    Fit {
        /// The fit.
        fit: Fit,
        /// The cross-validation's folds, if asked.
        folds: Option<Folds>,
        /// Offsets beside the compliances.
        offsets: bool,
    },
    /// The model comparison.
    Compare {
        /// The candidates by name; `None` for all.
        candidates: Option<Vec<String>>,
        /// The posture bootstrap, if asked.
        bootstrap: Option<Resampling>,
    },
}

/// Why `--offsets` takes no other fit or cross-validation.
const OFFSETS_ROBUST: &str = "the offsets are eliminated by centring each posture's and point's rows on their mean, which is exact for equal weights only (the weights of a robust fit would need a weighted centring at every iteration)";
const OFFSETS_NONNEGATIVE: &str = "the non-negative fit's standard errors and degrees of freedom would not count the offsets (3 unknowns per posture and point)";
const OFFSETS_FOLDS: &str = "a held-out posture's offsets are unknowns of that posture, so its deflection cannot be predicted";
const COMPARE: &str =
    "the comparison holds out posture by posture and compares least-squares fits without offsets";

impl Options {
    /// The options set, as [`JobOption`]s, among `all`.
    fn set(&self, all: &[JobOption]) -> Vec<JobOption> {
        all.iter().copied().filter(|o| self.is_set(*o)).collect()
    }

    fn is_set(&self, option: JobOption) -> bool {
        match option {
            JobOption::Robust => self.robust.is_some(),
            JobOption::Nonnegative => self.nonnegative,
            JobOption::CrossValidate => self.cross_validate,
            JobOption::Folds => self.folds.is_some(),
            JobOption::Offsets => self.offsets,
            JobOption::CompareModels => self.compare_models,
            JobOption::Candidates => self.candidates.is_some(),
            JobOption::Bootstrap => self.bootstrap.is_some(),
            JobOption::Seed => self.seed.is_some(),
            _ => false,
        }
    }

    /// Checks the options together, as the job does first: a front end may call it before it
    /// opens any file.
    ///
    /// # Errors
    /// Those of the job's check (below).
    pub fn check(&self) -> Result<()> {
        self.plan().map(|_| ())
    }

    /// The options checked together: what they ask for.
    ///
    /// # Errors
    /// [`Error::OptionCombination`] for options that cannot go together (`robust` and
    /// `nonnegative`; `offsets` with `robust`, `nonnegative`, `cross_validate` or `folds`;
    /// `compare_models` with any of those) or one set without the option it needs
    /// (`candidates` and `bootstrap` without `compare_models`, `seed` without `bootstrap`).
    pub(super) fn plan(&self) -> Result<Plan> {
        use JobOption as O;
        let needs = |option, with| match self.is_set(option) && !self.is_set(with) {
            true => Err(refused(option, vec![with], true, "")),
            false => Ok(()),
        };
        needs(O::Candidates, O::CompareModels)?;
        needs(O::Bootstrap, O::CompareModels)?;
        needs(O::Seed, O::Bootstrap)?;
        let not_with = |option, others: &[JobOption], reason: &str| {
            let with = self.set(others);
            match self.is_set(option) && !with.is_empty() {
                true => Err(refused(option, with, false, reason)),
                false => Ok(()),
            }
        };
        not_with(
            O::CompareModels,
            &[
                O::Robust,
                O::Nonnegative,
                O::CrossValidate,
                O::Folds,
                O::Offsets,
            ],
            COMPARE,
        )?;
        not_with(O::Offsets, &[O::Robust], OFFSETS_ROBUST)?;
        not_with(O::Offsets, &[O::Nonnegative], OFFSETS_NONNEGATIVE)?;
        not_with(O::Offsets, &[O::CrossValidate, O::Folds], OFFSETS_FOLDS)?;
        not_with(O::Robust, &[O::Nonnegative], "choose one")?;
        if self.compare_models {
            let bootstrap = self.bootstrap.map(|resamples| Resampling {
                resamples,
                seed: self.seed.unwrap_or(1),
            });
            return Ok(Plan::Compare {
                candidates: self.candidates.clone(),
                bootstrap,
            });
        }
        let fit = match (self.robust, self.nonnegative) {
            (Some(loss), _) => Fit::Robust(loss),
            (None, true) => Fit::Nonnegative,
            (None, false) => Fit::LeastSquares,
        };
        let folds = match (self.folds, self.cross_validate) {
            (Some(k), _) => Some(Folds::Count(k)),
            (None, true) => Some(Folds::LeaveOneOut),
            (None, false) => None,
        };
        Ok(Plan::Fit {
            fit,
            folds,
            offsets: self.offsets,
        })
    }
}

fn refused(option: JobOption, with: Vec<JobOption>, needs: bool, reason: &str) -> Error {
    Error::OptionCombination {
        option,
        with,
        needs,
        reason: reason.into(),
    }
}
