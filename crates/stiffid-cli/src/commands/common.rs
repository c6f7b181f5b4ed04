//! The options most commands share, flattened into their arguments (`#[command(flatten)]`).

use crate::load;
use anyhow::Result;
use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use std::ffi::OsStr;
use std::marker::PhantomData;
use std::path::PathBuf;
use stiffid::internal::common::choice::Choice;
use stiffid::internal::model::Compliance;
use stiffid::Setup;

/// `--setup` and `--json`, of every command that works with a setup and prints a result.
#[derive(clap::Args)]
pub struct Common {
    /// Setup: a built-in name (see `stiffid setups`) or a setup .toml file.
    #[arg(long)]
    pub setup: String,
    /// Print the result as JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

impl Common {
    /// The setup named by `--setup` ([`load::setup`]).
    pub fn load_setup(&self) -> Result<Setup> {
        load::setup(&self.setup)
    }
}

/// `--stiffness`, of the commands that use an identified stiffness.
#[derive(clap::Args)]
pub struct Stiffness {
    /// Stiffness file: JSON with every parameter of the setup's model (`parameters`) and
    /// optionally its covariance, as `stiffid identify --out` writes it; or, for the six drives
    /// alone, `stiffness_nm_per_rad` (Nm/rad) and optionally `compliance_covariance_rad2_per_nm2`.
    #[arg(long)]
    pub stiffness: PathBuf,
}

impl Stiffness {
    /// The compliance of every parameter of `setup`'s model from the file named by `--stiffness`
    /// ([`load::stiffness`]).
    pub fn load(&self, setup: &Setup) -> Result<Compliance> {
        load::stiffness(&self.stiffness, setup)
    }
}

/// The clap value parser of a library choice ([`Choice`]): its names as the possible values (with
/// their help), clap's own error for any other value. `#[arg(value_parser = choice::<T>())]`.
pub fn choice<T: Choice + Send + Sync>() -> ChoiceParser<T> {
    ChoiceParser(PhantomData)
}

/// See [`choice`].
#[derive(Clone)]
pub struct ChoiceParser<T>(PhantomData<T>);

impl<T: Choice + Send + Sync> ChoiceParser<T> {
    fn values() -> impl Iterator<Item = PossibleValue> {
        T::ALL
            .iter()
            .map(|v| PossibleValue::new(v.name()).help(v.help()))
    }
}

impl<T: Choice + Send + Sync> TypedValueParser for ChoiceParser<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> std::result::Result<T, clap::Error> {
        let name = PossibleValuesParser::new(Self::values()).parse_ref(cmd, arg, value)?;
        Ok(*T::ALL
            .iter()
            .find(|v| v.name() == name)
            .expect("a possible value"))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(Self::values()))
    }
}

/// The command line that runs this command, as a shell reads it: `stiffid` and its arguments,
/// each with a space, a quote or a shell character single-quoted.
pub fn command_line() -> String {
    let quote = |a: String| match a.is_empty()
        || a.chars()
            .any(|c| !(c.is_ascii_alphanumeric() || "-_./=,:+@%".contains(c)))
    {
        true => format!("'{}'", a.replace('\'', "'\\''")),
        false => a,
    };
    std::iter::once("stiffid".to_string())
        .chain(
            std::env::args_os()
                .skip(1)
                .map(|a| quote(a.to_string_lossy().into_owned())),
        )
        .collect::<Vec<_>>()
        .join(" ")
}
