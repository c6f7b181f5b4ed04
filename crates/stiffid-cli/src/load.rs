//! Turning command-line arguments into robots, setups and angle lists.

use anyhow::{bail, Context, Result};
use nalgebra::{Matrix6, SVector, Vector6};
use std::path::Path;
use stiffid::deflection::Frame;
use stiffid::formats::measurements::{self, MeasurementFile};
use stiffid::robot::{file, presets, urdf};
use stiffid::{setup, Robot, Setup};

/// A robot from a preset name, a robot `.toml` file or a `.urdf` file (`tip`: URDF tip link).
pub fn robot(arg: &str, tip: Option<&str>) -> Result<Robot> {
    let path = Path::new(arg);
    match path.extension().and_then(|e| e.to_str()) {
        Some("toml") => Ok(file::parse(&read(path)?, arg)?),
        Some("urdf") => Ok(urdf::parse(&read(path)?, arg, tip)?),
        _ => Ok(presets::get(arg)?),
    }
}

/// A setup from a built-in name or a setup `.toml` file. A robot file named in a setup file is
/// looked for relative to the setup file.
pub fn setup(arg: &str) -> Result<Setup> {
    let path = Path::new(arg);
    if path.extension().and_then(|e| e.to_str()) != Some("toml") {
        return Ok(setup::builtin(arg)?);
    }
    setup_text(&read(path)?, arg, path.parent().unwrap_or(Path::new("")))
}

/// A setup from its TOML `text`, read from `source_name` in the directory `dir` (where a robot
/// file it names is looked for).
pub fn setup_text(text: &str, source_name: &str, dir: &Path) -> Result<Setup> {
    let arg = source_name;
    Ok(setup::parse(text, arg, |r, tip| {
        let candidate = dir.join(r);
        // A preset name (which may hold a dot, as "nj165-3.0") wins over a file that is not there.
        let is_preset = presets::get(r).is_ok() && !candidate.exists();
        let reference = match Path::new(r).extension() {
            Some(_) if !is_preset => candidate.to_string_lossy().into_owned(),
            _ => r.to_string(),
        };
        robot(&reference, tip).map_err(|e| stiffid::Error::Parse {
            source_name: format!("{arg}: robot"),
            message: e.to_string(),
        })
    })?)
}

/// The text of a file, with its name in the error.
pub fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("{}: cannot read", path.display()))
}

/// A `--q-deg` posture: six comma-separated axis angles in degrees, within the robot's joint
/// limits. Returns the angles in degrees and in radians; the error names the axis and the limits.
pub fn posture(text: &str, robot: &Robot) -> Result<(Vector6<f64>, Vector6<f64>)> {
    let q_deg = six(text, "--q-deg")?;
    let q = q_deg.map(f64::to_radians);
    if let Some(i) = robot.first_out_of_limits(&q) {
        bail!(
            "--q-deg: axis {} = {} deg is outside the joint limits [{:.2}, {:.2}] deg of {}",
            i + 1,
            q_deg[i],
            robot.lower[i].to_degrees(),
            robot.upper[i].to_degrees(),
            robot.name
        );
    }
    Ok((q_deg, q))
}

/// Six comma-separated finite numbers, e.g. `--q-deg 0,0,-90,0,0,0`; `what` names the option.
pub fn six(text: &str, what: &str) -> Result<Vector6<f64>> {
    vector(text, what)
}

/// Exactly `N` comma-separated finite numbers, e.g. `--point-mm 150,0,200`; `what` names the option.
pub fn vector<const N: usize>(text: &str, what: &str) -> Result<SVector<f64, N>> {
    let values = numbers(text, what)?;
    if values.len() != N {
        bail!(
            "{what}: expected {N} comma-separated numbers, got {}",
            values.len()
        );
    }
    Ok(SVector::from_column_slice(&values))
}

/// Comma-separated finite numbers; `what` names the option in errors.
pub fn numbers(text: &str, what: &str) -> Result<Vec<f64>> {
    text.split(',')
        .enumerate()
        .map(|(i, s)| {
            let v: f64 = s.trim().parse().with_context(|| {
                format!("{what}: value {} '{}' is not a number", i + 1, s.trim())
            })?;
            if !v.is_finite() {
                bail!("{what}: value {} '{}' is not finite", i + 1, s.trim());
            }
            Ok(v)
        })
        .collect()
}

/// The joint stiffness (Nm/rad) in a JSON file's key `stiffness_nm_per_rad`: six finite numbers
/// > 0, for example the result of `stiffid identify --out`. Other keys are ignored.
pub fn stiffness(path: &Path) -> Result<Vector6<f64>> {
    Ok(identified(path)?.stiffness)
}

/// A stiffness file's joint stiffness and, if it has the key `compliance_covariance_rad2_per_nm2`
/// (6x6, (rad/Nm)^2, as `stiffid identify --out` writes it), the covariance of the compliance.
pub struct Identified {
    /// Nm/rad.
    pub stiffness: Vector6<f64>,
    /// `Cov(h)`, (rad/Nm)^2: finite, symmetric, non-negative diagonal.
    pub covariance: Option<Matrix6<f64>>,
}

/// Reads a stiffness file (see [`Identified`]); other keys are ignored.
pub fn identified(path: &Path) -> Result<Identified> {
    #[derive(serde::Deserialize)]
    struct StiffnessFile {
        stiffness_nm_per_rad: [f64; 6],
        compliance_covariance_rad2_per_nm2: Option<[[f64; 6]; 6]>,
    }
    let name = path.display();
    let file: StiffnessFile = serde_json::from_str(&read(path)?).with_context(|| {
        format!("{name}: expected JSON with the key stiffness_nm_per_rad (six numbers, Nm/rad) and optionally compliance_covariance_rad2_per_nm2 (6x6)")
    })?;
    let k = Vector6::from(file.stiffness_nm_per_rad);
    if let Some(j) = (0..6).find(|&j| !(k[j].is_finite() && k[j] > 0.0)) {
        bail!(
            "{name}: stiffness_nm_per_rad[{j}] = {}: expected a finite number > 0",
            k[j]
        );
    }
    let covariance = match file.compliance_covariance_rad2_per_nm2 {
        None => None,
        Some(rows) => {
            let c = Matrix6::from_fn(|r, col| rows[r][col]);
            let scale = c.diagonal().amax();
            let valid = c.iter().all(|v| v.is_finite())
                && c.diagonal().iter().all(|v| *v >= 0.0)
                && (c - c.transpose()).amax() <= 1e-9 * scale;
            if !valid {
                bail!("{name}: compliance_covariance_rad2_per_nm2: expected a symmetric 6x6 matrix of finite numbers with a non-negative diagonal");
            }
            Some(c)
        }
    };
    Ok(Identified {
        stiffness: k,
        covariance,
    })
}

/// The frame of a wrench, as a command-line value.
#[derive(Clone, Copy, Default, clap::ValueEnum)]
pub enum WrenchFrame {
    /// The robot base frame.
    #[default]
    Base,
    /// The tool (flange) frame, moving with the tool.
    Tool,
}

impl From<WrenchFrame> for Frame {
    fn from(f: WrenchFrame) -> Self {
        match f {
            WrenchFrame::Base => Frame::Base,
            WrenchFrame::Tool => Frame::Tool,
        }
    }
}

/// A measurement file (`stiffid::formats::measurements`), its measurements turned into the robot
/// base frame; errors start with the file name, then the line and column. The text is dropped
/// once parsed.
pub fn measurements(path: &Path, setup: &Setup) -> Result<MeasurementFile> {
    let name = || path.display().to_string();
    let mut file = measurements::parse(&read(path)?).with_context(name)?;
    file.to_base_frame(setup).with_context(name)?;
    Ok(file)
}
