//! How to compensate a path: what the free variables minimise, and the options of the Newton
//! steps.

use nalgebra::Vector6;
use stiffid_core::robot::ik;
use stiffid_core::Setup;

/// The free variable a map is drawn over (`compensate --map rotation|track`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MapVariable {
    /// The rotation about tool z (the free tool axis).
    #[default]
    Rotation,
    /// The track station (the carrier's first axis, the free station).
    Track,
}

impl stiffid_core::common::choice::Choice for MapVariable {
    const FIELD: &'static str = "map";
    const ALL: &'static [Self] = &[MapVariable::Rotation, MapVariable::Track];
    fn name(self) -> &'static str {
        match self {
            MapVariable::Rotation => "rotation",
            MapVariable::Track => "track",
        }
    }
    fn help(self) -> &'static str {
        match self {
            MapVariable::Rotation => "The rotation about the spindle (tool z)",
            MapVariable::Track => "The track station (a robot on a track)",
        }
    }
}

stiffid_core::common::choice::by_name!(MapVariable);

/// How to compensate a path.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Where inverse kinematics starts for the first pose, axis angles, rad.
    pub q0: Vector6<f64>,
    /// Inverse kinematics tolerances and effort.
    pub ik: ik::Options,
    /// The free variables and what they minimise ([`super::FreeVariables`]; none by default).
    pub free: super::FreeVariables,
    /// The level of the prediction intervals of the deflection (with a compliance that carries
    /// a prediction calibration, [`stiffid_core::model::prediction`]), within
    /// 0.5 to 0.999.
    pub level: f64,
    /// Newton steps at most per point, 1 to [`super::MAX_ITERATIONS`] (the default).
    pub max_iterations: usize,
    /// The process force model's relative error, in [0, 1] (default
    /// [`super::budget::DEFAULT_FORCE_TOLERANCE`]): the error budget's force part
    /// ([`super::Budget`]).
    pub force_tolerance: f64,
    /// The largest error bound the compensate job accepts anywhere on the path, m (> 0, finite):
    /// a path with a point above it is refused (`stiffid::app::compensate::run`); `None` accepts
    /// any.
    pub max_error: Option<f64>,
    /// What every posture the free variables move a point to must keep: the joint-limit margin,
    /// the condition number and the cell's collision checks ([`super::Feasible`]).
    pub feasible: super::Feasible,
    /// The compensate job also maps the free variable ([`super::Map`]: every point at every
    /// value of the grid of [`Options::map_over`]); [`super::path`] ignores it.
    pub map: bool,
    /// The variable of the map: the rotation about tool z (the default) or the track station.
    pub map_over: MapVariable,
    /// Levels of refinement of the free variables' grid around the line chosen on it, 0 to
    /// 4 (module docs of [`super`], "Refining the grid"); 0: the
    /// grid alone.
    pub refine: usize,
}

impl Options {
    /// The defaults for `setup`: inverse kinematics starts at the setup's first test posture (else
    /// the middle of its bounds), with [`ik::Options::default`]; no free tool axis; at most
    /// [`super::MAX_ITERATIONS`] Newton steps per point; the feasibility of
    /// [`super::Feasible::for_setup`].
    pub fn for_setup(setup: &Setup) -> Self {
        let bounds = setup.bounds();
        Self {
            q0: setup
                .test_postures()
                .first()
                .copied()
                .unwrap_or((bounds.lower + bounds.upper) / 2.0),
            ik: ik::Options::default(),
            free: super::FreeVariables::default(),
            level: stiffid_core::model::prediction::DEFAULT_LEVEL,
            max_iterations: super::MAX_ITERATIONS,
            force_tolerance: super::budget::DEFAULT_FORCE_TOLERANCE,
            max_error: None,
            feasible: super::Feasible::for_setup(setup),
            map: false,
            map_over: MapVariable::Rotation,
            refine: 0,
        }
    }
}
