//! Warnings: results the user must look at before trusting them, raised by every stage and
//! shown by every front end the same way.

use serde::Serialize;

/// What a [`Warning`] is about: a stable code for programs (`kind.code()`), independent of the
/// message's wording.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum WarningKind {
    /// Every identified compliance is negative: a sign convention is probably wrong.
    AllNegative,
    /// Some identified compliances are negative: not physical.
    Negative,
    /// Some identified compliances are zero or not finite: the joint looks rigid.
    Rigid,
    /// A unit mistake is likely or possible: the identified stiffness is far off the setup's
    /// nominal the same way on most joints, or a G-code program states no units (`G20`, `G21`)
    /// before it moves and is read in mm.
    Units,
    /// An input passes every range check but looks like a unit slip (lengths in metres where
    /// millimetres are meant, angles in radians under `_deg` names:
    /// [`crate::setup::plausibility`]) or a convention slip (a FANUC LS program's joint values
    /// on a URDF robot whose axes the setup does not couple).
    Plausibility,
    /// Under load steps, some postures' zero-load offset, departure from a straight line or
    /// hysteresis exceeds what the tracker noise explains (`stiffid_identify::steps`).
    LoadSteps,
    /// Points of a machining program get no process force (plunges, rapid moves, blocks no
    /// operation covers).
    NoForce,
    /// The data cannot separate some parameters of the model: they get no interval
    /// (`stiffid_identify::svd::Identifiability`).
    Unidentifiable,
    /// A URDF's collision meshes were not found: the robot serves kinematics and identification,
    /// the cell's body checks refuse it ([`crate::robot::Bodies::Missing`]).
    Meshes,
    /// A model's residuals exceed what the tracker noise explains by more than
    /// `stiffid::app::calibrate::MISFIT_RATIO` times: the model misses something.
    Misfit,
    /// A generated robot program states a feed only to its nearest unit (an LS feed in neither
    /// whole mm/sec nor whole cm/min).
    Feed,
    /// Two postures of a designed group are near in axis angles or reach the same flange pose
    /// (`stiffid_design::distinct`).
    NearPostures,
    /// A setup field under its old name: it still reads, and the warning says what it meant
    /// (`[noise] variance_mm2`, [`crate::setup::Noise`]).
    OldField,
    /// An iterative solver stopped before it converged (the robust reweighting at its
    /// iteration limit): its result may still move.
    NotConverged,
    /// The robot's masses are placeholders (or unusable): no mass matrix, natural frequencies
    /// or surge ([`crate::robot::dynamics::MassModel::new`]).
    Masses,
    /// A milling point's first natural frequency is near a harmonic of the tooth-passing
    /// frequency (`stiffid_machining::dynamics`).
    Chatter,
    /// The free configuration kept the path's own for want of another, or left it because it
    /// cannot take the path (`stiffid_machining::compensate::FreeConfiguration`).
    Configuration,
    /// A file written leaves out part of the model or of what was asked: a URDF holds no joint
    /// error map ([`crate::robot::ErrorMap`]), an INFORM job no Cartesian target.
    LeftOut,
    /// A posture or path point lies outside the region the stiffness was identified from, or
    /// the stiffness file does not record that region ([`crate::model::region`]).
    Extrapolation,
    /// A robot program's linear moves whose programmed speed stiffid does not read: the axes'
    /// speed limits are not checked there (`stiffid_machining::program::speed`).
    Speed,
    /// A setup field that repeats what a calibrated robot file holds (its mount): taken from the
    /// calibration, not applied twice.
    Calibrated,
    /// The stiffness file's model and the recommended model the data support rank a path's
    /// postures differently (`stiffid::app::compensate`, its `model_ranking`).
    ModelForm,
    /// A program's files are not UTF-8: read as Latin-1 and written back in it
    /// ([`crate::io::program_texts`]).
    Encoding,
}

impl WarningKind {
    /// The stable code, e.g. `units`.
    pub fn code(self) -> &'static str {
        match self {
            WarningKind::AllNegative => "all-negative",
            WarningKind::Negative => "negative",
            WarningKind::Rigid => "rigid",
            WarningKind::Units => "units",
            WarningKind::Plausibility => "plausibility",
            WarningKind::LoadSteps => "load-steps",
            WarningKind::NoForce => "no-force",
            WarningKind::Unidentifiable => "unidentifiable",
            WarningKind::Meshes => "meshes",
            WarningKind::Misfit => "misfit",
            WarningKind::Feed => "feed",
            WarningKind::NearPostures => "near-postures",
            WarningKind::OldField => "old-field",
            WarningKind::NotConverged => "not-converged",
            WarningKind::Masses => "masses",
            WarningKind::Chatter => "chatter",
            WarningKind::LeftOut => "left-out",
            WarningKind::Configuration => "configuration",
            WarningKind::Extrapolation => "extrapolation",
            WarningKind::Speed => "speed",
            WarningKind::Calibrated => "calibrated",
            WarningKind::ModelForm => "model-form",
            WarningKind::Encoding => "encoding",
        }
    }
}

/// A result the user must look at before trusting it: what the command line prints as
/// `warning: MESSAGE` and Python raises as `UserWarning(MESSAGE)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Warning {
    /// What it is about.
    pub kind: WarningKind,
    /// One sentence for the user: what was found and its likely cause.
    pub message: String,
}

impl Warning {
    /// A warning of `kind` saying `message`.
    pub fn new(kind: WarningKind, message: impl Into<String>) -> Self {
        Warning {
            kind,
            message: message.into(),
        }
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// `joint 3` or `joints 1, 2` for 0-based joint indices.
pub fn joint_list(joints: impl IntoIterator<Item = usize>) -> String {
    let names: Vec<String> = joints.into_iter().map(|j| (j + 1).to_string()).collect();
    match names.len() {
        1 => format!("joint {}", names[0]),
        _ => format!("joints {}", names.join(", ")),
    }
}
