//! `stiffid kinematics`: forward kinematics, point Jacobian and dexterity of one posture.

use crate::commands::common::choice;
use crate::{load, output};
use anyhow::{Context, Result};
use stiffid::app::kinematics as job;
use stiffid::app::kinematics::document::Document;
use stiffid::{internal::common::limits, Coordinates};

/// Arguments of `stiffid kinematics`.
#[derive(clap::Args)]
pub struct Args {
    /// A preset name (see `stiffid robots`), a robot .toml file or a .urdf file.
    #[arg(long, required_unless_present = "setup", conflicts_with = "setup")]
    robot: Option<String>,
    /// A setup (a built-in name or a setup .toml file) instead of --robot: its robot with the
    /// setup's base, flange and external axes, and its [workpiece] as the part's frame.
    #[arg(long)]
    setup: Option<String>,
    /// URDF only: the tip link of the chain (default: the only leaf link, else the leaf ending the
    /// chain of six revolute joints, else tool0).
    #[arg(long, conflicts_with = "setup")]
    tip: Option<String>,
    /// The external axes' values of a cell with external axes (a track, a positioner), in the
    /// cell's order (carrier first, then positioner), comma-separated: mm for a linear axis, deg
    /// for a rotary one, each within its travel. Required for such a cell, refused without one.
    #[arg(long, allow_hyphen_values = true)]
    external: Option<String>,
    /// The posture: six axis angles in degrees, comma-separated, e.g. 0,0,-90,0,0,0.
    #[arg(long, allow_hyphen_values = true)]
    q_deg: String,
    /// A point in the flange frame, mm, comma-separated (default: the flange origin); each
    /// coordinate within +-100000 mm.
    #[arg(long, allow_hyphen_values = true, default_value = "0,0,0")]
    point_mm: String,
    /// The characteristic length L of the dexterity index k(J_N) (Eq. 20), mm [1 to 100000]
    /// (default: with --setup, the setup's `characteristic_length_mm`; else derived from the
    /// robot, the length that minimises the point's median dexterity over its joint limits).
    #[arg(long)]
    characteristic_length_mm: Option<f64>,
    /// The joint coordinates of the Jacobian's columns.
    #[arg(long, value_parser = choice::<Coordinates>(), default_value = "axis")]
    coordinates: Coordinates,
    /// The six joints' stiffness, Nm/rad, comma-separated, in the coordinates of
    /// `--coordinates` [1 to 1e10 each]: the natural frequencies and mode shapes of the posture
    /// with the robot's masses (a robot file's mass_kg, com_mm, inertia_kg_m2 or a URDF's
    /// <inertial>).
    #[arg(long)]
    stiffness_nm_per_rad: Option<String>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// Prints the kinematics of one posture.
pub fn run(args: &Args) -> Result<()> {
    // A setup's characteristic length is the one to use unless one is given.
    let (robot, workpiece, length) = match (&args.setup, &args.robot) {
        (Some(s), _) => {
            let setup = load::setup(s)?;
            let length = setup.characteristic_length();
            (setup.robot().clone(), setup.workpiece().copied(), length)
        }
        (None, Some(r)) => (load::robot(r, args.tip.as_deref())?, None, None),
        (None, None) => anyhow::bail!("give --robot or --setup"),
    };
    let (_, q) = load::posture(&args.q_deg, "--q-deg", &robot)?;
    let external = external(args.external.as_deref(), &robot)?;
    job::check_external(&robot, &external, "--external")?;
    let point = load::vector::<3>(&args.point_mm, "--point-mm", &limits::LENGTH_MM)? * 1e-3;
    let stiffness = (args.stiffness_nm_per_rad.as_deref())
        .map(|k| load::vector::<6>(k, "--stiffness-nm-per-rad", &limits::STIFFNESS_NM_PER_RAD))
        .transpose()?;
    let request = job::Request {
        robot: &robot,
        q,
        point,
        characteristic_length: (args.characteristic_length_mm.map(|l| l * 1e-3)).or(length),
        coordinates: args.coordinates,
        stiffness,
        external,
        workpiece,
    };
    let outcome = job::run(&request).with_context(|| match args.characteristic_length_mm {
        Some(_) => "--characteristic-length-mm",
        None => "give --characteristic-length-mm",
    })?;
    output::warnings(&outcome.warnings);
    output::print_json_or(args.json, outcome.written(), |r| text(&r.document()))
}

fn text(r: &Document<'_>) -> String {
    let (unit, var) = match r.coordinates {
        Coordinates::Axis => ("axis angles", "q"),
        Coordinates::Kinematic => ("kinematic angles", "theta"),
    };
    let mut s = format!("{}\nsource: {}\n", r.robot, r.robot_source);
    s += &format!("posture q_deg: {}\n", list(&r.q_deg, 2));
    s += &format!("flange position_mm: {}\n", list(&r.flange_position_mm, 3));
    let frame = match r.external.is_empty() {
        true => "base frame",
        false => "cell frame",
    };
    s += &format!("flange rotation ({frame}; columns: flange x, y, z axes):\n");
    for row in &r.flange_rotation {
        s += &format!("  {}\n", list(row, 6));
    }
    s += &format!(
        "point in flange frame_mm: {}\npoint position_mm: {}\n",
        list(&r.point_mm, 3),
        list(&r.point_position_mm, 3)
    );
    s += &format!(
        "Jacobian of the point ({frame}, {unit}; rows vx vy vz in m/rad, wx wy wz in rad/rad):\n"
    );
    s += "      ";
    for j in 1..=6 {
        s += &format!("{:>11}", format!("{var}{j}"));
    }
    s += "\n";
    for (row, name) in r.jacobian.iter().zip(["vx", "vy", "vz", "wx", "wy", "wz"]) {
        s += &format!("  {name:<4}");
        for v in row {
            s += &format!("{:>11}", fixed(*v, 6));
        }
        s += "\n";
    }
    if let Some(j) = &r.external_jacobian {
        s += &format!(
            "external axes: {}\n",
            (r.external.iter())
                .map(|e| format!(
                    "{} ({}, {}) = {}",
                    e.column,
                    e.name,
                    e.role,
                    fixed(e.value, 3)
                ))
                .collect::<Vec<_>>()
                .join(", ")
        );
        s += "Jacobian columns of the external axes (cell frame, the point relative to the part; rows vx vy vz in m/m or m/rad, wx wy wz in rad/rad):\n      ";
        for e in &r.external {
            s += &format!("{:>11}", e.column);
        }
        s += "\n";
        for (row, name) in j.iter().zip(["vx", "vy", "vz", "wx", "wy", "wz"]) {
            s += &format!("  {name:<4}");
            for v in row {
                s += &format!("{:>11}", fixed(*v, 6));
            }
            s += "\n";
        }
    }
    if let (Some(p), Some(rot), Some(x)) =
        (&r.part_position_mm, &r.part_rotation, &r.point_in_part_mm)
    {
        s += &format!("part frame position_mm: {}\n", list(p, 3));
        s += "part frame rotation (cell frame; columns: part x, y, z axes):\n";
        for row in rot {
            s += &format!("  {}\n", list(row, 6));
        }
        s += &format!("point in part frame_mm: {}\n", list(x, 3));
    }
    let k = match r.dexterity {
        Some(k) => fixed(k, 4),
        None => "infinite (singular posture)".into(),
    };
    let source = match r.characteristic_length_source {
        "given" => "given",
        _ => "derived from the robot: minimises the point's median dexterity",
    };
    s += &format!(
        "dexterity k(J_N) (L = {} mm, {source}): {k}\n",
        fixed(r.characteristic_length_mm, 1)
    );
    if let Some(f) = &r.natural_frequencies_hz {
        s += &format!("natural frequencies Hz: {}\n", list(f, 2));
    }
    s
}

/// The values of `--external` in SI (the cell's order), checked by the job; empty without it.
fn external(text: Option<&str>, robot: &stiffid::Robot) -> Result<Vec<f64>> {
    let Some(text) = text else {
        return Ok(Vec::new());
    };
    let values = load::numbers(text, "--external", &limits::EXTERNAL_VALUE)?;
    Ok(match robot.external() {
        Some(axes) if axes.len() == values.len() => axes.to_si(&values),
        // The job's check names the axes and the count expected.
        _ => values,
    })
}

/// `v` with `decimals` digits after the point, without a sign on a value that rounds to zero.
pub fn fixed(v: f64, decimals: usize) -> String {
    let scale = 10f64.powi(decimals as i32);
    let rounded = (v * scale).round() / scale + 0.0;
    format!("{rounded:.decimals$}")
}

/// Numbers joined by ", " with `decimals` digits after the point.
fn list<const N: usize>(values: &[f64; N], decimals: usize) -> String {
    values
        .iter()
        .map(|v| fixed(*v, decimals))
        .collect::<Vec<_>>()
        .join(", ")
}
