//! The options most commands share, flattened into their arguments (`#[command(flatten)]`).

use crate::load;
use anyhow::Result;
use std::path::PathBuf;
use stiffid::formats::stiffness::StiffnessFile;
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
    /// Stiffness file: JSON with `stiffness_nm_per_rad` (six values, Nm/rad) and optionally
    /// `compliance_covariance_rad2_per_nm2`, e.g. from `stiffid identify --out`.
    #[arg(long)]
    pub stiffness: PathBuf,
}

impl Stiffness {
    /// The stiffness file named by `--stiffness` ([`load::stiffness`]).
    pub fn load(&self) -> Result<StiffnessFile> {
        load::stiffness(&self.stiffness)
    }
}
