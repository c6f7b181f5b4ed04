//! `stiffid kinematics`: forward kinematics, point Jacobian and dexterity of one posture.

use crate::commands::common::choice;
use crate::{load, output};
use anyhow::{Context, Result};
use schemars::JsonSchema;
use serde::Serialize;
use stiffid::{dexterity, limits, prior, Coordinates};

/// Arguments of `stiffid kinematics`.
#[derive(clap::Args)]
pub struct Args {
    /// A preset name (see `stiffid robots`), a robot .toml file or a .urdf file.
    #[arg(long)]
    robot: String,
    /// URDF only: the tip link of the chain (default: the only leaf link, else the leaf ending the
    /// chain of six revolute joints, else tool0).
    #[arg(long)]
    tip: Option<String>,
    /// The posture: six axis angles in degrees, comma-separated, e.g. 0,0,-90,0,0,0.
    #[arg(long, allow_hyphen_values = true)]
    q_deg: String,
    /// A point in the flange frame, mm, comma-separated (default: the flange origin); each
    /// coordinate within +-100000 mm.
    #[arg(long, allow_hyphen_values = true, default_value = "0,0,0")]
    point_mm: String,
    /// The characteristic length L of the dexterity index k(J_N) (Eq. 20), mm [1 to 100000]
    /// (default: derived from the robot, the length that minimises the point's median dexterity
    /// over its joint limits; a setup's `characteristic_length_mm` is the one to give).
    #[arg(long)]
    characteristic_length_mm: Option<f64>,
    /// The joint coordinates of the Jacobian's columns.
    #[arg(long, value_parser = choice::<Coordinates>(), default_value = "axis")]
    coordinates: Coordinates,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// `stiffid kinematics --json`: mm and degrees for positions and angles, SI (m/rad, rad/rad) for
/// the Jacobian, rows `[v; omega]`; base frame.
#[derive(Serialize, JsonSchema)]
pub struct Report {
    /// The robot's name.
    robot: String,
    /// Where the robot comes from (for a URDF: the file and the tip link used).
    robot_source: String,
    /// Axis angles q1..q6, deg.
    q_deg: [f64; 6],
    /// The joint coordinates of the Jacobian's columns.
    coordinates: Coordinates,
    /// The characteristic length of the dexterity index, mm.
    characteristic_length_mm: f64,
    /// Where it comes from: `given` (`--characteristic-length-mm`) or `derived` from the robot
    /// (the length minimising the point's median dexterity over the joint limits,
    /// `stiffid::prior::robot_characteristic_length`).
    characteristic_length_source: &'static str,
    /// The point of the Jacobian, flange frame, mm.
    point_mm: [f64; 3],
    /// The flange's origin, mm.
    flange_position_mm: [f64; 3],
    /// Rotation matrix of the flange frame in the base frame, row-major.
    flange_rotation: [[f64; 3]; 3],
    /// The point's position, mm.
    point_position_mm: [f64; 3],
    /// Row-major, rows vx, vy, vz (m/rad), wx, wy, wz (rad/rad); column j is joint j.
    jacobian: [[f64; 6]; 6],
    /// The dexterity index k(J_N) (Eq. 20): 1 for an isotropic Jacobian, larger is worse; `null`
    /// at a singularity.
    #[schemars(with = "Option<f64>")]
    dexterity: f64,
    /// Origin of each joint frame (after the joint), base frame.
    joint_positions_mm: [[f64; 3]; 6],
}

/// Prints the kinematics of one posture.
pub fn run(args: &Args) -> Result<()> {
    let robot = load::robot(&args.robot, args.tip.as_deref())?;
    let (q_deg, q) = load::posture(&args.q_deg, "--q-deg", &robot)?;
    let point_mm = load::vector::<3>(&args.point_mm, "--point-mm", &limits::LENGTH_MM)?;
    let point = point_mm * 1e-3;
    let (length_mm, source) = match args.characteristic_length_mm {
        Some(l) => {
            let range = &limits::CHARACTERISTIC_LENGTH_MM;
            limits::check("--characteristic-length-mm", &[l], range)?;
            (l, "given")
        }
        None => {
            let l = prior::robot_characteristic_length(&robot, &point)
                .context("give --characteristic-length-mm")?;
            (l * 1e3, "derived")
        }
    };
    let coordinates = args.coordinates;
    let frames = robot.frames(&q);
    let jacobian = frames.jacobian(&point, coordinates);
    let report = Report {
        robot: robot.name().to_string(),
        robot_source: robot.source().to_string(),
        q_deg: q_deg.into(),
        coordinates,
        characteristic_length_mm: length_mm,
        characteristic_length_source: source,
        point_mm: point_mm.into(),
        flange_position_mm: (frames.flange.translation.vector * 1e3).into(),
        flange_rotation: rows(&frames.flange.rotation.to_rotation_matrix().into_inner()),
        point_position_mm: (frames.point(&point) * 1e3).into(),
        jacobian: rows(&jacobian),
        dexterity: dexterity(&jacobian, length_mm * 1e-3),
        joint_positions_mm: frames.joints.map(|f| (f.translation.vector * 1e3).into()),
    };
    output::print_json_or(args.json, &report, text)
}

/// A matrix as an array of rows.
fn rows<const R: usize, const C: usize>(m: &nalgebra::SMatrix<f64, R, C>) -> [[f64; C]; R] {
    std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)]))
}

fn text(r: &Report) -> String {
    let (unit, var) = match r.coordinates {
        Coordinates::Axis => ("axis angles", "q"),
        Coordinates::Kinematic => ("kinematic angles", "theta"),
    };
    let mut s = format!("{}\nsource: {}\n", r.robot, r.robot_source);
    s += &format!("posture q_deg: {}\n", list(&r.q_deg, 2));
    s += &format!("flange position_mm: {}\n", list(&r.flange_position_mm, 3));
    s += "flange rotation (base frame; columns: flange x, y, z axes):\n";
    for row in &r.flange_rotation {
        s += &format!("  {}\n", list(row, 6));
    }
    s += &format!(
        "point in flange frame_mm: {}\npoint position_mm: {}\n",
        list(&r.point_mm, 3),
        list(&r.point_position_mm, 3)
    );
    s += &format!(
        "Jacobian of the point (base frame, {unit}; rows vx vy vz in m/rad, wx wy wz in rad/rad):\n"
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
    let k = match r.dexterity {
        k if k.is_finite() => fixed(k, 4),
        _ => "infinite (singular posture)".into(),
    };
    let source = match r.characteristic_length_source {
        "given" => "given",
        _ => "derived from the robot: minimises the point's median dexterity",
    };
    s += &format!(
        "dexterity k(J_N) (L = {} mm, {source}): {k}\n",
        fixed(r.characteristic_length_mm, 1)
    );
    s
}

/// `v` with `decimals` digits after the point, without a sign on a value that rounds to zero.
fn fixed(v: f64, decimals: usize) -> String {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_row_major() {
        let m = nalgebra::Matrix2x3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
        assert_eq!(rows(&m), [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]);
    }

    #[test]
    fn fixed_drops_the_sign_of_zero() {
        assert_eq!(fixed(-1e-14, 3), "0.000");
        assert_eq!(fixed(-0.0006, 3), "-0.001");
        assert_eq!(fixed(2074.0000000000005, 3), "2074.000");
    }
}
