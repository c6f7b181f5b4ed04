//! The elastostatic model: the six drive springs plus any number of virtual springs.
//!
//! The Virtual Joint Method with link springs (Deblaise, Hernot, Maurine, "A systematic analytical
//! method for PKM stiffness matrix calculation", ICRA 2006; Klimchik, Caro, Furet, Pashkevich,
//! "Complete stiffness model for a serial robot", ICINCO 2014): besides one torsional spring per
//! drive (Zhang et al. 2021, Eq. 3-8), a **virtual spring** is the compliance `c >= 0` of a
//! one-degree-of-freedom virtual joint fixed in one body of the chain, link k (k = 0 the base,
//! k = 1..6 the body after joint k, 6 carrying the flange and the tool):
//! - a rotation about the axis `u` through the point `o`, both fixed in link k's frame;
//! - a translation along the direction `u`, fixed in link k's frame.
//!
//! Link k's frame is the robot file's own frame k (for a DH table the DH frame k, for a URDF the
//! child link of joint k: [`crate::Frames::joints`]); link 0's is the robot's base frame.
//!
//! At a posture, with `u` and `o` in the base frame, the spring's Jacobian column at a point `p`
//! (base frame) is `[u x (p - o); u]` (rotation) or `[u; 0]` (translation), as a drive's column
//! `[z_j x (p - o_j); z_j]`. Under the wrench `W` at the loading point it deflects by
//! `c (J_f,s^T W)` and moves a measuring point by `c J_m,s (J_f,s^T W)`: one more column of the
//! observation matrix, built as Eq. 11 builds the drive columns ([`crate::observation`]).
//!
//! Parameters are numbered drives first (`k1` .. `k6`), then the virtual springs in the order of
//! the setup. SI inside: compliances in rad/Nm (drives, rotations) and m/N (translations);
//! files and reports speak Nm/rad and N/mm ([`Unit`]).

mod compliance;
mod family;
pub(crate) mod file;
pub(crate) mod form;
mod law;
pub mod prediction;
pub mod region;

pub use crate::robot::OwnWeight;
pub use compliance::Compliance;
pub(crate) use family::check_declared_names;
pub use family::Family;
pub use file::{fragment, parse as parse_fragment};
pub use form::{FormModel, ModelForm};
pub use law::{Law, DEFAULT_SMOOTHING};
pub use region::{PostureRange, Region};

use crate::robot::kinematics::{Coordinates, Frames};
use crate::{Error, Result};
use nalgebra::{DVector, Isometry3, Point3, Unit as UnitVector, Vector3, Vector6};

pub(crate) use crate::common::limits::MAX_VIRTUAL_SPRINGS;

/// Longest spring name, characters.
pub(crate) const MAX_NAME_CHARS: usize = 40;

/// What a virtual joint does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// A rotation about an axis through a point (compliance rad/Nm).
    Rotation,
    /// A translation along a direction (compliance m/N).
    Translation,
}

impl Kind {
    /// The unit of a nominal stiffness in files (`nominal_stiffness_nm_per_rad`,
    /// `nominal_stiffness_n_per_mm`), whatever the spring's law: a lost motion's or a
    /// load-dependent compliance's nominal stiffness is a stiffness too.
    pub(crate) fn stiffness_unit(self) -> Unit {
        match self {
            Kind::Rotation => Unit::NmPerRad,
            Kind::Translation => Unit::NPerMm,
        }
    }
}

/// The unit of a parameter's stiffness in files and reports; for a nonlinear law's parameter
/// ([`Law`]), which has no stiffness, the unit of the parameter itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// Nm/rad (drives and rotational springs); SI inside, the same number.
    NmPerRad,
    /// N/mm (translational springs); N/m inside, 1000 times the number.
    NPerMm,
    /// urad: a lost motion `b` (rad inside).
    Urad,
    /// urad/kNm^2: a load-dependent compliance `c1` (rad/Nm^2 inside, 1e12 times the number).
    UradPerKnm2,
}

impl Unit {
    /// Stiffness in this unit per SI stiffness (Nm/rad or N/m); for [`Unit::Urad`] and
    /// [`Unit::UradPerKnm2`] the parameter in this unit per SI parameter.
    pub fn per_si(self) -> f64 {
        match self {
            Unit::NmPerRad => 1.0,
            Unit::NPerMm => 1e-3,
            Unit::Urad => 1e6,
            Unit::UradPerKnm2 => 1e12,
        }
    }

    /// Whether the unit is a stiffness's (reported as `1 / h`), not a parameter's own.
    pub fn is_stiffness(self) -> bool {
        matches!(self, Unit::NmPerRad | Unit::NPerMm)
    }

    /// What a report shows of the SI compliance-side parameter `h`: the stiffness `1 / h` or,
    /// for a nonlinear law's parameter, `h` itself, in this unit.
    pub fn reported(self, h: f64) -> f64 {
        match self.is_stiffness() {
            true => self.per_si() / h,
            false => self.per_si() * h,
        }
    }

    /// The unit as written after a number (`Nm/rad`, `N/mm`, `urad`, `urad/kNm^2`).
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::NmPerRad => "Nm/rad",
            Unit::NPerMm => "N/mm",
            Unit::Urad => "urad",
            Unit::UradPerKnm2 => "urad/kNm^2",
        }
    }

    /// The unit as a field-name suffix (`nm_per_rad`, `n_per_mm`, `urad`, `urad_per_knm2`).
    pub(crate) fn suffix(self) -> &'static str {
        match self {
            Unit::NmPerRad => "nm_per_rad",
            Unit::NPerMm => "n_per_mm",
            Unit::Urad => "urad",
            Unit::UradPerKnm2 => "urad_per_knm2",
        }
    }
}

/// A virtual spring: the compliance of a 1-DoF virtual joint fixed in link `link` (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Spring {
    /// Its name in reports and files (letters, digits, `_` and `-`; not `k1` .. `k6`).
    pub name: String,
    /// Rotation or translation.
    pub kind: Kind,
    /// The body it is fixed in: 0 the base, 1..6 the link after joint k.
    pub link: usize,
    /// The axis (rotation) or direction (translation), unit, in link `link`'s frame.
    pub axis: UnitVector<Vector3<f64>>,
    /// A point of the rotation axis, link frame, m (unused by a translation).
    pub point: Vector3<f64>,
    /// Nominal stiffness for the design criteria: Nm/rad (rotation) or N/m (translation), SI.
    pub nominal_stiffness: Option<f64>,
    /// How it deflects under its load ([`Law`]; a spring's is linear). Only the observation
    /// matrix (identification and the model comparison) applies a nonlinear law: a setup file
    /// declares such joints only as candidates, and prediction, compensation and the design
    /// criteria take every virtual spring as linear.
    pub law: Law,
}

/// A spring at a posture: its axis and point in the base frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// Rotation or translation.
    pub kind: Kind,
    /// Unit axis or direction, base frame.
    pub u: Vector3<f64>,
    /// A point of the axis, base frame, m.
    pub o: Vector3<f64>,
}

impl Placed {
    /// The translation part of the Jacobian column at the base-frame point `p`:
    /// `u x (p - o)` (rotation, m/rad) or `u` (translation, m/m).
    #[inline(always)]
    pub fn velocity(&self, p: &Vector3<f64>) -> Vector3<f64> {
        match self.kind {
            Kind::Rotation => self.u.cross(&(p - self.o)),
            Kind::Translation => self.u,
        }
    }

    /// The Jacobian column `[u x (p - o); u]` or `[u; 0]` at the base-frame point `p`.
    pub fn column(&self, p: &Vector3<f64>) -> Vector6<f64> {
        let v = self.velocity(p);
        let w = match self.kind {
            Kind::Rotation => self.u,
            Kind::Translation => Vector3::zeros(),
        };
        Vector6::new(v.x, v.y, v.z, w.x, w.y, w.z)
    }

    /// The generalised force `J_s^T W` of the wrench `[f; m]` (N, Nm, base frame) at the
    /// base-frame point `p`: Nm (rotation) or N (translation).
    #[inline(always)]
    pub fn load(&self, p: &Vector3<f64>, wrench: &Vector6<f64>) -> f64 {
        let f = wrench.fixed_rows::<3>(0);
        match self.kind {
            Kind::Rotation => self.velocity(p).dot(&f) + self.u.dot(&wrench.fixed_rows::<3>(3)),
            Kind::Translation => self.u.dot(&f),
        }
    }
}

impl Spring {
    /// The unit of its stiffness in files and reports (of its parameter for a nonlinear law).
    pub fn unit(&self) -> Unit {
        match (self.law, self.kind) {
            (Law::LostMotion { .. }, _) => Unit::Urad,
            (Law::LoadDependent, _) => Unit::UradPerKnm2,
            (Law::Linear, Kind::Rotation) => Unit::NmPerRad,
            (Law::Linear, Kind::Translation) => Unit::NPerMm,
        }
    }

    /// Its generalised load's response (`Law::response`) under the wrench `[f; m]` (base
    /// frame) at the loading point `p` (base frame) at a posture where it is `placed`.
    #[inline(always)]
    pub fn response(&self, placed: &Placed, p: &Vector3<f64>, wrench: &Vector6<f64>) -> f64 {
        self.law.response(placed.load(p, wrench))
    }

    /// Its axis and point in the base frame at the posture `frames`.
    pub fn placed(&self, frames: &Frames) -> Placed {
        let frame = link_frame(frames, self.link);
        Placed {
            kind: self.kind,
            u: frame.rotation * self.axis.into_inner(),
            o: (frame * Point3::from(self.point)).coords,
        }
    }
}

/// The frame of link `link` (0 the base, [`Frames::base`]: on a carrier the carriage's mount;
/// 1..6 [`Frames::joints`]) at a posture, base frame.
///
/// # Panics
/// If `link > 6`.
pub(crate) fn link_frame(frames: &Frames, link: usize) -> &Isometry3<f64> {
    match link {
        0 => &frames.base,
        k => &frames.joints[k - 1],
    }
}

/// What a parameter of a model is: a drive spring or a virtual spring of either kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
pub enum ParameterKind {
    /// One of the six drive springs (Nm/rad).
    Drive,
    /// A rotational virtual spring (Nm/rad).
    Rotation,
    /// A translational virtual spring (N/mm).
    Translation,
    /// A lost motion ([`Law::LostMotion`], urad).
    LostMotion,
    /// A load-dependent compliance ([`Law::LoadDependent`], urad/kNm^2).
    LoadDependent,
}

impl ParameterKind {
    /// The name in files: `drive`, `rotation`, `translation`, `lost-motion`, `load-dependent`.
    pub fn name(self) -> &'static str {
        match self {
            ParameterKind::Drive => "drive",
            ParameterKind::Rotation => "rotation",
            ParameterKind::Translation => "translation",
            ParameterKind::LostMotion => "lost-motion",
            ParameterKind::LoadDependent => "load-dependent",
        }
    }
}

/// One parameter of a model: its name, kind and unit.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// `k1` .. `k6` for the drives, the spring's name otherwise.
    pub name: String,
    /// A drive, a rotational or a translational spring.
    pub kind: ParameterKind,
    /// The unit of its stiffness.
    pub unit: Unit,
}

/// The elastostatic model (module docs): the six drive springs in `coordinates` and the virtual
/// springs. The default is the drives alone in axis coordinates.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Model {
    coordinates: Coordinates,
    springs: Vec<Spring>,
}

/// The names of the drive parameters.
pub(crate) const DRIVE_NAMES: [&str; 6] = ["k1", "k2", "k3", "k4", "k5", "k6"];

impl Model {
    /// The six drive springs alone, in `coordinates`.
    pub fn drives(coordinates: Coordinates) -> Self {
        Self {
            coordinates,
            springs: Vec::new(),
        }
    }

    /// The drives in `coordinates` and the virtual springs `springs`, checked (`check_springs`).
    ///
    /// # Errors
    /// As `check_springs`.
    pub fn new(coordinates: Coordinates, springs: Vec<Spring>) -> Result<Self> {
        check_springs(&springs)?;
        Ok(Self {
            coordinates,
            springs,
        })
    }

    /// Where the drive springs sit.
    pub fn coordinates(&self) -> Coordinates {
        self.coordinates
    }

    /// The virtual springs, in parameter order after the drives.
    pub fn springs(&self) -> &[Spring] {
        &self.springs
    }

    /// The number of parameters: 6 plus the virtual springs.
    pub fn len(&self) -> usize {
        6 + self.springs.len()
    }

    /// Never: a model has at least the six drives.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Whether the model is the six drives alone (the paper's).
    pub fn is_drives_only(&self) -> bool {
        self.springs.is_empty()
    }

    /// The parameters, drives first.
    pub fn parameters(&self) -> Vec<Parameter> {
        let drives = DRIVE_NAMES.iter().map(|n| Parameter {
            name: (*n).to_string(),
            kind: ParameterKind::Drive,
            unit: Unit::NmPerRad,
        });
        let springs = self.springs.iter().map(|s| Parameter {
            name: s.name.clone(),
            kind: match (s.law, s.kind) {
                (Law::LostMotion { .. }, _) => ParameterKind::LostMotion,
                (Law::LoadDependent, _) => ParameterKind::LoadDependent,
                (Law::Linear, Kind::Rotation) => ParameterKind::Rotation,
                (Law::Linear, Kind::Translation) => ParameterKind::Translation,
            },
            unit: s.unit(),
        });
        drives.chain(springs).collect()
    }

    /// The nominal compliance of every parameter (rad/Nm, m/N), drives from `drives` (Nm/rad),
    /// when every spring has a nominal stiffness.
    pub(crate) fn nominal_compliance(&self, drives: &Vector6<f64>) -> Option<DVector<f64>> {
        let springs: Option<Vec<f64>> = self
            .springs
            .iter()
            .map(|s| s.nominal_stiffness.map(|k| 1.0 / k))
            .collect();
        let springs = springs?;
        Some(DVector::from_iterator(
            self.len(),
            drives.iter().map(|k| 1.0 / k).chain(springs),
        ))
    }

    /// The same model with the springs `more` added after its own.
    ///
    /// # Errors
    /// As `check_springs` for the combined list.
    pub fn with(&self, more: &[Spring]) -> Result<Self> {
        let mut springs = self.springs.clone();
        springs.extend_from_slice(more);
        Self::new(self.coordinates, springs)
    }

    /// The virtual springs placed at the posture `frames`.
    pub fn placed(&self, frames: &Frames) -> Vec<Placed> {
        self.springs.iter().map(|s| s.placed(frames)).collect()
    }

    /// The augmented Jacobian `[J_q | J_s1 .. J_sv]` (6 x n, base frame, rows `[v; omega]`) of
    /// the tool point `point` (flange frame, m) at the posture `frames`: the drive
    /// columns in the model's coordinates ([`Frames::jacobian`]), then each virtual spring's
    /// column `[u x (p - o); u]` or `[u; 0]` ([`Placed::column`]). A tool point sits beyond every
    /// link, so every spring moves it. With it, `tau = J_a^T W` are the loads of every parameter
    /// (Nm or N), `J_b diag(h) J_a^T W` a tool point's deflection and `J diag(h) J^T` the
    /// Cartesian compliance ([`crate::observation::cartesian`]).
    pub(crate) fn jacobian(
        &self,
        frames: &Frames,
        point: &Vector3<f64>,
    ) -> nalgebra::Matrix6xX<f64> {
        let mut j = nalgebra::Matrix6xX::zeros(self.len());
        j.fixed_columns_mut::<6>(0)
            .copy_from(&frames.jacobian(point, self.coordinates));
        let p = frames.point(point);
        for (s, spring) in self.springs.iter().enumerate() {
            j.set_column(6 + s, &spring.placed(frames).column(&p));
        }
        j
    }
}

/// Checks a list of virtual springs: at most [`MAX_VIRTUAL_SPRINGS`]; each name non-empty, at
/// most `MAX_NAME_CHARS` letters, digits, `_` or `-`, unique and not a drive's (`k1` .. `k6`);
/// `link` 0 to 6; `axis` finite and non-zero; `point` finite within
/// [`crate::common::limits::LENGTH_MM`]; a nominal stiffness within
/// [`crate::common::limits::STIFFNESS_NM_PER_RAD`] (rotation) or [`crate::common::limits::STIFFNESS_N_PER_MM`]
/// (translation). Fields are named as in a setup file (`model.spring[2].link`).
///
/// # Errors
/// [`Error::InvalidField`] for the first problem.
pub(crate) fn check_springs(springs: &[Spring]) -> Result<()> {
    crate::common::limits::check_count("model.spring", springs.len(), 0, MAX_VIRTUAL_SPRINGS)?;
    for (i, s) in springs.iter().enumerate() {
        let field = |f: &str| format!("model.spring[{}].{f}", i + 1);
        check_name(&s.name, &field("name"))?;
        if springs[..i].iter().any(|t| t.name == s.name) {
            return Err(invalid(
                &field("name"),
                format!("'{}' names two springs: names must be unique", s.name),
            ));
        }
        if s.link > 6 {
            return Err(invalid(
                &field("link"),
                format!("{} is not a link: expected 0 (base) to 6", s.link),
            ));
        }
        let axis = s.axis.into_inner();
        crate::common::limits::check(
            &field("axis"),
            axis.as_slice(),
            &crate::common::limits::AXIS,
        )?;
        let mm: Vec<f64> = s.point.iter().map(|v| v * 1e3).collect();
        crate::common::limits::check(&field("point_mm"), &mm, &crate::common::limits::LENGTH_MM)?;
        if let Some(k) = s.nominal_stiffness {
            let range = match s.kind {
                Kind::Rotation => crate::common::limits::STIFFNESS_NM_PER_RAD,
                Kind::Translation => crate::common::limits::STIFFNESS_N_PER_MM,
            };
            let unit = s.kind.stiffness_unit();
            let name = format!("nominal_stiffness_{}", unit.suffix());
            crate::common::limits::check(&field(&name), &[k * unit.per_si()], &range)?;
        }
    }
    Ok(())
}

fn check_name(name: &str, field: &str) -> Result<()> {
    let allowed = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
    if name.is_empty() || name.chars().count() > MAX_NAME_CHARS || !name.chars().all(allowed) {
        return Err(invalid(
            field,
            format!(
                "'{}' is not a spring name: expected 1 to {MAX_NAME_CHARS} letters, digits, '_' or '-'",
                crate::common::limits::short(name)
            ),
        ));
    }
    if DRIVE_NAMES.contains(&name) {
        return Err(invalid(
            field,
            format!("'{name}' is a drive's name: choose another"),
        ));
    }
    Ok(())
}

fn invalid(field: &str, message: String) -> Error {
    Error::InvalidField {
        field: field.to_string(),
        message,
    }
}

/// A unit axis from a finite, non-zero vector (any length), or the error naming `field`.
///
/// # Errors
/// [`Error::InvalidField`] for a non-finite or zero vector.
pub(crate) fn unit_axis(v: Vector3<f64>, field: &str) -> Result<UnitVector<Vector3<f64>>> {
    crate::common::limits::check(field, v.as_slice(), &crate::common::limits::AXIS)?;
    UnitVector::try_new(v, 1e-12).ok_or_else(|| {
        invalid(
            field,
            "the zero vector has no direction: expected a non-zero axis".into(),
        )
    })
}

#[cfg(test)]
mod law_tests;
#[cfg(test)]
mod model_tests;
#[cfg(test)]
mod prediction_tests;
#[cfg(test)]
mod region_tests;
