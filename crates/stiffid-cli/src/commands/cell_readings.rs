//! The arguments `stiffid register` and `stiffid calibrate-cell` share (`--setup`, `--json`,
//! `--data`, `--out`) and their one way to run a job on the readings, write the fragment and
//! print the document.

use crate::commands::common::Common;
use crate::load;
use crate::output::{self, print_json_or, OutFile};
use anyhow::{bail, Result};
use serde::Serialize;
use std::path::PathBuf;
use stiffid::app::register::Request;
use stiffid::internal::common::warning::Warning;
use stiffid::Setup;

/// `--setup`, `--json`, `--data` and `--out`.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: Common,
    /// Readings CSV: posture,point,q1_deg..q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm, one row
    /// per posture and measuring point (at most 100000 rows; with load steps, the unloaded
    /// readings are used).
    #[arg(long)]
    pub data: Option<PathBuf>,
    /// Write the fragment of the setup file here (TOML; never over an input); with `register
    /// --count`, the readings CSV to fill in.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Fit readings that no rigid transform explains (a mirror image of the robot's points, or a
    /// residual beyond the larger of 10 mm and 1000 times the tracker noise) instead of refusing
    /// them.
    #[arg(long, requires = "data")]
    pub force: bool,
}

/// What a job on the readings gives the command: its document, the fragment to write with
/// `--out` and its warnings.
pub struct Outcome<D> {
    /// The document printed (text or `--json`).
    pub document: D,
    /// The setup-file fragment `--out` writes.
    pub fragment: String,
    /// The job's warnings.
    pub warnings: Vec<Warning>,
}

impl Args {
    /// The setup of `--setup`.
    pub fn setup(&self) -> Result<Setup> {
        self.common.load_setup()
    }

    /// Reads `--data`, runs `job` on it, writes the fragment with `--out` (prepared first, so a
    /// refused output costs no computation), prints the warnings and the document (`text` or
    /// JSON).
    pub fn run<D: Serialize>(
        &self,
        setup: &Setup,
        job: impl FnOnce(&Request<'_>) -> stiffid::Result<Outcome<D>>,
        text: impl FnOnce(&D) -> String,
    ) -> Result<()> {
        let Some(path) = &self.data else {
            bail!("--data: expected the readings CSV");
        };
        let content = load::read(path)?;
        let out = self.prepare_out()?;
        let request = Request {
            setup,
            setup_name: self.common.setup.clone(),
            name: path.display().to_string(),
            text: &content,
            force: self.force,
        };
        let outcome = job(&request)?;
        output::warnings(&outcome.warnings);
        if let Some(out) = &out {
            out.write(outcome.fragment.as_bytes())?;
        }
        print_json_or(self.common.json, &outcome.document, text)
    }

    /// `--out`, checked and ready to be written.
    pub fn prepare_out(&self) -> Result<Option<OutFile>> {
        let prepare = |p: &PathBuf| OutFile::prepare(p, "--out");
        self.out.as_ref().map(prepare).transpose()
    }
}

/// Three numbers with `digits` decimals, comma-separated.
pub fn three(v: [f64; 3], digits: usize) -> String {
    format!("{:.digits$}, {:.digits$}, {:.digits$}", v[0], v[1], v[2])
}
