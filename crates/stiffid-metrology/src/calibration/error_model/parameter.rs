//! The parameters of the error model: which joint errors are fitted ([`Geometry`]), the frame
//! the readings are in, and each parameter's kind, target, name, unit and nominal value.

use crate::calibration::gravity;
use serde::Serialize;

/// Which joint errors a calibration fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Geometry {
    /// None: the frame and the measuring points only (the cell calibration).
    None,
    /// The joint angle offsets `theta`.
    Offsets,
    /// Every joint error: `theta`, `d`, `a`, `alpha`, Hayati's `beta` and `b` (the dependent ones
    /// merged).
    #[default]
    Full,
}

impl stiffid_core::common::choice::Choice for Geometry {
    const FIELD: &'static str = "geometry";
    const ALL: &'static [Self] = &[Geometry::None, Geometry::Offsets, Geometry::Full];
    fn name(self) -> &'static str {
        match self {
            Geometry::None => "none",
            Geometry::Offsets => "offsets",
            Geometry::Full => "full",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Geometry::None => "The frame and the measuring points only (the cell calibration)",
            Geometry::Offsets => "Also the joint angle offsets",
            Geometry::Full => "Every joint error: theta, d, a, alpha, beta, b (dependent merged)",
        }
    }
}

stiffid_core::common::choice::by_name!(Geometry);

/// The frame the readings are in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum MeasuredIn {
    /// The tracker's frame: the frame parameters are the tracker's registration.
    Tracker,
    /// The robot base frame (a tracker already registered): the frame parameters are the base
    /// frame's error.
    Base,
}

/// One error of a joint, in its rotation frame's basis `(u, v, w)` ([`super::Basis`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Component {
    /// The joint angle offset: rotation about the axis `w`, rad.
    Theta,
    /// Translation along the axis `w`, m.
    D,
    /// Translation along `u`, m.
    A,
    /// Rotation about `u`, rad.
    Alpha,
    /// Rotation about `v` (Hayati's beta), rad.
    Beta,
    /// Translation along `v`, m.
    B,
}

impl Component {
    /// All six, in the order of the parameter list.
    pub const ALL: [Component; 6] = [
        Component::Theta,
        Component::D,
        Component::A,
        Component::Alpha,
        Component::Beta,
        Component::B,
    ];

    /// The name in parameter names: `theta`, `d`, `a`, `alpha`, `beta`, `b`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Component::Theta => "theta",
            Component::D => "d",
            Component::A => "a",
            Component::Alpha => "alpha",
            Component::Beta => "beta",
            Component::B => "b",
        }
    }

    /// Whether it is an angle (rad) rather than a length (m).
    pub fn is_angle(self) -> bool {
        matches!(self, Component::Theta | Component::Alpha | Component::Beta)
    }
}

/// What a parameter moves.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Target {
    /// The measurement frame: 0-2 translation along the base frame's x, y, z (m), 3-5 rotation
    /// about them (rad).
    Frame(usize),
    /// A measuring point's coordinate (0 x, 1 y, 2 z) in the flange frame, m; points 0-based.
    Point {
        /// The measuring point, 0-based.
        point: usize,
        /// The coordinate: 0 x, 1 y, 2 z.
        axis: usize,
    },
    /// A joint error; joints 0-based.
    Joint {
        /// The joint, 0-based.
        joint: usize,
        /// The error.
        component: Component,
    },
    /// A gravity term ([`gravity::Term`]).
    Gravity(gravity::Term),
    /// The compliance of parameter `index` (0-based, drives first) of the setup's stiffness
    /// model under the wrenches of loaded readings ([`super::ErrorModel::with_loads`]): rad/(N m), m/N
    /// (or a nonlinear law's parameter, [`stiffid_core::model::Law`]).
    Compliance {
        /// The parameter of the setup's model, 0-based (drives `0..6`, then the virtual
        /// springs).
        index: usize,
        /// What it is: a drive, a rotational or translational spring, a nonlinear law's.
        kind: stiffid_core::model::ParameterKind,
    },
    /// A coefficient of joint `joint`'s error map ([`stiffid_core::robot::ErrorMap`], rad): of
    /// `cos(h q)` or, with `sine`, of `sin(h q)`, `h = harmonic` (1-based), `q` the joint's axis
    /// angle ([`super::ErrorModel::with_maps`]).
    Map {
        /// The joint, 0-based.
        joint: usize,
        /// The harmonic `h`, 1-based.
        harmonic: usize,
        /// Whether it is the sine's coefficient (else the cosine's).
        sine: bool,
    },
    /// Half the backlash of joint `joint` (0-based, rad, [`stiffid_core::robot::ErrorMap::backlash`]):
    /// its angle error's `+ b d`, `d` the sign of the joint's last motion
    /// ([`super::Observation::direction`], [`super::ErrorModel::with_maps`]).
    Backlash {
        /// The joint, 0-based.
        joint: usize,
    },
    /// A parameter of external axis `axis` (0-based, the cell's order:
    /// [`stiffid_core::robot::ExternalAxes`]).
    External {
        /// The axis, 0-based in the cell's order.
        axis: usize,
        /// What it moves.
        part: AxisPart,
    },
    /// A coordinate (0 x, 1 y, 2 z) of a reflector fixed in the cell (on the positioner's table,
    /// or a fixed point of a cell without a positioner), part frame at `e = 0` (cell
    /// coordinates), m; reflectors 0-based.
    Table {
        /// The reflector, 0-based.
        point: usize,
        /// The coordinate: 0 x, 1 y, 2 z.
        axis: usize,
    },
}

/// What a parameter of an external axis moves ([`super::ErrorModel::with_external`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AxisPart {
    /// The axis's direction turned about its nominal frame's y (0) or z (1) axis
    /// ([`stiffid_core::robot::external::ExternalAxis::frame`]), rad.
    Direction(usize),
    /// A linear axis's error motion coefficient of `u^order` (`order` 1-based; `motion` 0
    /// positioning, 1 and 2 straightness along the frame's y and z, 3 roll, 4 pitch, 5 yaw),
    /// m or rad.
    Motion {
        /// The power of `u`, 1-based.
        order: usize,
        /// The motion, ISO 230-1's six in [`stiffid_core::robot::external::ErrorMotions`] order.
        motion: usize,
    },
    /// A rotary axis's line moved along its nominal frame's y (0) or z (1) axis, m.
    Location(usize),
    /// A rotary axis's angular offset, rad.
    Offset,
    /// A linear axis's zero offset: its carriage moved along its direction, m (fitted by an
    /// update only, [`super::ErrorModel::with_external_offsets`]).
    Shift,
}

impl AxisPart {
    /// Whether it is an angle (rad) rather than a length (m).
    pub(crate) fn is_angle(self) -> bool {
        match self {
            AxisPart::Direction(_) | AxisPart::Offset => true,
            AxisPart::Motion { motion, .. } => motion >= 3,
            AxisPart::Location(_) | AxisPart::Shift => false,
        }
    }
}

/// The kind of a parameter, as documents name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// The tracker's registration.
    Tracker,
    /// The robot base frame's error (readings in the base frame).
    Base,
    /// A measuring point in the flange frame.
    Point,
    /// A joint's geometric error.
    Joint,
    /// A compliance: of a joint under gravity (known masses), or of a parameter of the setup's
    /// stiffness model under the applied wrenches (loaded readings).
    Compliance,
    /// A lumped gravity term: a compliance times a mass moment.
    Gravity,
    /// A coefficient of a joint's error map.
    Map,
    /// A parameter of a carrier's linear axis: its direction or an error motion's coefficient.
    Carrier,
    /// A parameter of a positioner's rotary axis: its line's location and direction, its
    /// angular offset.
    Positioner,
    /// A coordinate of a reflector fixed in the cell (on the positioner's table, or fixed).
    Table,
}

impl Kind {
    /// The name in documents.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Tracker => "tracker",
            Kind::Base => "base",
            Kind::Point => "point",
            Kind::Joint => "joint",
            Kind::Compliance => "compliance",
            Kind::Gravity => "gravity",
            Kind::Map => "map",
            Kind::Carrier => "carrier",
            Kind::Positioner => "positioner",
            Kind::Table => "table",
        }
    }
}

/// One parameter of the error model.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// Its name: `tracker.x`, `point2.z`, `joint3.beta`, `gravity.c2`, `track.pitch.u2`,
    /// `table1.x` ... (unique).
    pub name: String,
    /// Its kind.
    pub kind: Kind,
    /// What it moves.
    pub target: Target,
    /// Its nominal value, SI (m, rad, rad/(N m), ...): 0 for an error, the setup's coordinate for
    /// a measuring point, the nominal compliance (or 0) for a compliance.
    pub nominal: f64,
    /// The order in which [`crate::calibration::identifiability`] keeps parameters: lower first
    /// (0 the frame, the points, the table's reflectors, a carrier's directions and a
    /// positioner's lines, 1 the (M)DH errors, 2 `beta`, the error motions and the positioner's offsets,
    /// 3 `b`, 4 the gravity terms, 5 the error maps' coefficients).
    pub priority: u8,
}

impl Parameter {
    /// The unit in documents (mm, deg, ...).
    pub fn unit(&self) -> &'static str {
        match self.target {
            Target::Frame(i) if i < 3 => "mm",
            Target::Frame(_) => "deg",
            Target::Point { .. } => "mm",
            Target::Joint { component, .. } if component.is_angle() => "deg",
            Target::Joint { .. } => "mm",
            Target::Map { .. } | Target::Backlash { .. } => "deg",
            Target::External {
                part: AxisPart::Offset,
                ..
            } => "deg",
            Target::External { part, .. } if part.is_angle() => "mrad",
            Target::External { .. } | Target::Table { .. } => "mm",
            Target::Gravity(term) => term.unit(),
            Target::Compliance { kind, .. } => compliance_unit(kind),
        }
    }

    /// The factor from SI to the document's unit.
    pub fn document_factor(&self) -> f64 {
        match self.unit() {
            "mm" => 1e3,
            "deg" => 180.0 / std::f64::consts::PI,
            "mrad" => 1e3,
            _ => match self.target {
                Target::Gravity(term) => term.document_factor(),
                Target::Compliance { .. } => 1e6,
                _ => 1.0,
            },
        }
    }
}

/// The document unit of a compliance of `kind` (SI times 1e6): `urad/(N m)` of a drive or a
/// rotational spring, `um/N` of a translational one, `urad` of a lost motion, `urad/(N m)^2` of
/// a load-dependent compliance.
fn compliance_unit(kind: stiffid_core::model::ParameterKind) -> &'static str {
    use stiffid_core::model::ParameterKind as P;
    match kind {
        P::Drive | P::Rotation => "urad/(N m)",
        P::Translation => "um/N",
        P::LostMotion => "urad",
        P::LoadDependent => "urad/(N m)^2",
    }
}

/// The parameters of the gravity terms `terms` (priority 4), in their order.
pub(super) fn gravity_parameters(terms: &gravity::Terms) -> Vec<Parameter> {
    use gravity::Term;
    (terms.terms().iter())
        .map(|&t| Parameter {
            name: t.name(),
            kind: match t {
                Term::Compliance { .. } => Kind::Compliance,
                Term::Lumped { .. } | Term::Arm { .. } => Kind::Gravity,
            },
            target: Target::Gravity(t),
            nominal: terms.nominal(t),
            priority: 4,
        })
        .collect()
}
