//! `stiffid setups new --robot R`: a complete, commented setup for the user's own robot
//! ([`stiffid::app::setups_new`]). The text is loaded back before it is written, so it always
//! loads as written.

use crate::{load, output};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use stiffid::app::setups_new::{self as job, relative_to, robot_reference};
use stiffid::Robot;

/// Arguments of `stiffid setups new`.
#[derive(clap::Args)]
pub struct NewArgs {
    /// The robot: a preset name (see `stiffid robots`), a robot `.toml` file or a `.urdf` file.
    #[arg(long)]
    robot: String,
    /// URDF only: the tip link of the chain.
    #[arg(long)]
    tip: Option<String>,
    /// The robot's rated payload, kg (0.1 to 2500); sets the rough nominal stiffness.
    /// Default: a class guessed from the robot's reach.
    #[arg(long)]
    payload_kg: Option<f64>,
    /// Write the setup to this new file (an existing file is never replaced); default: stdout.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Writes (or prints) the setup.
pub fn run(args: &NewArgs) -> Result<()> {
    let robot = load::robot(&args.robot, args.tip.as_deref())?;
    let out = args
        .out
        .as_deref()
        .map(|p| output::OutFile::prepare_new(p, "--out"))
        .transpose()?;
    let at = args.out.as_deref();
    let robot_ref = robot_reference(&args.robot, at, "--robot")?;
    let package_paths = load::package_paths()
        .iter()
        .map(|p| relative_to(p, at, "--package-path"))
        .collect::<stiffid::Result<Vec<_>>>()?;
    let request = job::Request {
        robot: &robot,
        robot_ref: &robot_ref,
        tip: args.tip.as_deref(),
        package_paths: &package_paths,
        payload_kg: args.payload_kg,
    };
    let text = job::run(&request)?;
    let source_name = args
        .out
        .as_ref()
        .map_or("setups new".into(), |p| p.display().to_string());
    check_loads(&text, &source_name, args, &robot)?;
    match (&out, &args.out) {
        (Some(file), Some(path)) => {
            file.write(text.as_bytes())?;
            output::print(&format!(
                "setup for {} written to {}: edit the values under EDIT (tool, rope, pulley)\n",
                robot.name(),
                path.display()
            ))
        }
        _ => output::print(&text),
    }
}

/// Parses the generated text as `--setup` would read it from `--out`, with its own
/// `package_paths` only (not `--package-path`): it loads as written.
fn check_loads(text: &str, source_name: &str, args: &NewArgs, robot: &Robot) -> Result<()> {
    let dir = args
        .out
        .as_deref()
        .and_then(Path::parent)
        .unwrap_or(Path::new(""));
    let setup = load::setup_text_as_written(text, source_name, dir)
        .context("setups new: the generated setup does not load (please report this)")?;
    let missing = |r: &Robot| matches!(r.bodies(), stiffid::internal::robot::Bodies::Missing(_));
    if missing(setup.robot()) && !missing(robot) {
        anyhow::bail!(
            "setups new: the generated setup does not find the robot's meshes (please report this)"
        );
    }
    Ok(())
}
