//! The options of the jobs' requests a user sets directly ([`JobOption`]), named by
//! [`crate::Error::InvalidOption`] and [`crate::Error::OptionCombination`].

/// The options of the jobs' requests that a user sets directly (not fields of a file), named by
/// [`crate::Error::InvalidOption`]: one enum, so that a front end maps each to its own spelling without
/// matching names as strings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JobOption {
    /// select: the stations (external axis values) of a robot with external axes.
    Station,
    /// compensate: a free variable (`--free`, Python's `free=`).
    Free,
    /// compensate, place: how the points' costs add up along the path (sum or max).
    Objective,
    /// compensate: the free tool axis' largest change between consecutive points, deg.
    ToolRotationStep,
    /// compensate: how far the free tool axis may turn from the path's rotation, deg.
    ToolRotationRange,
    /// compensate: what the free tool axis minimises (the deflection, or the drilling surge).
    Minimise,
    /// compensate: how far the free track station may move from the path's own, mm.
    StationRange,
    /// compensate: the free track station's largest change between consecutive points, mm.
    StationStep,
    /// compensate: how far the free positioner may turn from the path's own angle, deg.
    PositionerRange,
    /// compensate: the free positioner's largest change between consecutive points, deg.
    PositionerStep,
    /// compensate: the tool axis' lead and tilt free within the cone.
    LeadTilt,
    /// compensate: the cone's half angle a path file's tool axis may lean within, deg.
    LeadTiltRange,
    /// compensate: the largest change of the lead and of the tilt between consecutive points,
    /// deg.
    LeadTiltStep,
    /// compensate: how far the free tilt (a two-axis positioner's first axis) may turn from
    /// the path's own angle, deg.
    TiltRange,
    /// compensate: the free tilt's largest change between consecutive points, deg.
    TiltStep,
    /// compensate: the robot's configuration chosen among the arm's (shoulder, elbow, wrist).
    Configuration,
    /// compensate: what one configuration of the free configuration holds (the program, or
    /// each run between rapid moves).
    ConfigurationScope,
    /// compensate: the free variable mapped (the tool rotation or the track station).
    Map,
    /// compensate: the largest error bound a program may have anywhere, mm.
    MaxErrorMm,
    /// compensate: the distance every moved posture keeps to the joint limits, deg.
    MarginDeg,
    /// compensate: the largest condition number of a moved posture's TCP Jacobian.
    MaxCondition,
    /// compensate: the levels of refinement of the free variables' grid.
    Refine,
    /// compensate: the process force model's relative error, percent.
    ForceTolerancePct,
    /// compensate: the largest sagitta of the chords of a G-code arc, mm.
    ChordToleranceMm,
    /// compensate: the robot's largest TCP speed, mm/s.
    MaxTcpSpeedMmS,
    /// compensate: what the targets of a robot program written from G-code are (Cartesian or
    /// joint).
    Targets,
    /// compensate: the longest program name the controller takes.
    NameLength,
    /// compensate: the most moves in one program file.
    MovesPerFile,
    /// compensate: the name of the robot program written (from the output file's name).
    ProgramName,
    /// select: the stiffness design criterion to minimise.
    Criterion,
    /// select: the local searches of a global search.
    Starts,
    /// select: the SQP steps of every global start before the best continue.
    ScreenSteps,
    /// select: the global starts that continue after the screening.
    Polished,
    /// select: the most criterion evaluations of a local search.
    MaxEvals,
    /// select: how a local search gets its gradient (exact or finite differences).
    Gradient,
    /// select: the SQP of the local searches.
    Solver,
    /// select: the target predicted deviation rate, %.
    TargetPct,
    /// select: the group a local search starts from.
    Start,
    /// select: the axis-angle and flange-orientation distance of distinct postures, deg.
    DistinctDeg,
    /// select: the flange-origin distance of distinct postures, mm.
    DistinctMm,
    /// select: the margin every posture keeps to every constraint of the cell, mm.
    MarginMm,
    /// select: design for the candidates of the model comparison.
    ForCandidates,
    /// identify --compare-models, select --for-candidates, evaluate: the candidate springs, by
    /// family or name.
    Candidates,
    /// calibrate: the nominal tolerances of the geometric errors (a length, mm, and an angle,
    /// deg), given together.
    Tolerances,
    /// calibrate: the bound on the gravity terms, the joint deflection each is held to at the
    /// largest torque it meets, mrad.
    GravityBoundMrad,
    /// calibrate: the joint error maps fitted (auto, none or joints with harmonics).
    Maps,
    /// calibrate: the orders of a carrier's error motions fitted (auto or an order).
    ErrorMotions,
    /// setups new: the robot's rated payload, kg.
    PayloadKg,
    /// setups new: the file the setup is written to.
    Out,
    /// identify --compare-models: the number of bootstrap resamples.
    Bootstrap,
    /// identify: the robust fit's loss.
    Robust,
    /// identify: the non-negative fit.
    Nonnegative,
    /// identify: cross-validation over postures.
    CrossValidate,
    /// identify: the number of cross-validation folds.
    Folds,
    /// identify: offsets per posture and measuring point beside the compliances.
    Offsets,
    /// identify: the model comparison.
    CompareModels,
    /// identify --compare-models --bootstrap: the seed of the resamples.
    Seed,
    /// select, evaluate: the calibration criterion (a calibration design only).
    CalibrationCriterion,
    /// select, evaluate: the joint errors the calibration fits (a calibration design only).
    Geometry,
    /// select, evaluate: the gravity terms the calibration fits (a calibration design only).
    Gravity,
    /// select, evaluate: the weight of the calibration's criterion (a design for both only).
    Weight,
    /// select: the exchange runs of a pool choice.
    Restarts,
    /// register: fit readings that no rigid transform explains (readings only).
    Force,
    /// predict, validate, compensate: the level of the prediction intervals.
    Level,
    /// calibrate: refit what drifts from a calibrated robot file.
    Update,
}

impl JobOption {
    /// The option's name as the library and Python spell it (`max_condition`); a free
    /// variable's range or step as `free station range`.
    pub fn name(self) -> &'static str {
        match self {
            JobOption::Station => "station",
            JobOption::Free => "free",
            JobOption::Objective => "objective",
            JobOption::ToolRotationStep => "free tool-rotation step",
            JobOption::ToolRotationRange => "free tool-rotation range",
            JobOption::Minimise => "minimise",
            JobOption::StationRange => "free station range",
            JobOption::StationStep => "free station step",
            JobOption::PositionerRange => "free positioner range",
            JobOption::PositionerStep => "free positioner step",
            JobOption::LeadTilt => "free lead-tilt",
            JobOption::LeadTiltRange => "free lead-tilt range",
            JobOption::LeadTiltStep => "free lead-tilt step",
            JobOption::TiltRange => "free tilt range",
            JobOption::TiltStep => "free tilt step",
            JobOption::Configuration => "free configuration",
            JobOption::ConfigurationScope => "free configuration",
            JobOption::Map => "map",
            JobOption::MaxErrorMm => "max_error_mm",
            JobOption::MarginDeg => "margin_deg",
            JobOption::MaxCondition => "max_condition",
            JobOption::Refine => "refine",
            JobOption::ForceTolerancePct => "force_tolerance_pct",
            JobOption::ChordToleranceMm => "chord_tolerance_mm",
            JobOption::MaxTcpSpeedMmS => "max_tcp_speed_mm_s",
            JobOption::Targets => "targets",
            JobOption::NameLength => "name_length",
            JobOption::MovesPerFile => "moves_per_file",
            JobOption::ProgramName => "name",
            JobOption::Criterion => "criterion",
            JobOption::Starts => "starts",
            JobOption::ScreenSteps => "screen_steps",
            JobOption::Polished => "polished",
            JobOption::MaxEvals => "max_evals",
            JobOption::Gradient => "gradient",
            JobOption::Solver => "solver",
            JobOption::TargetPct => "target_pct",
            JobOption::Start => "start",
            JobOption::DistinctDeg => "distinct_deg",
            JobOption::DistinctMm => "distinct_mm",
            JobOption::MarginMm => "margin_mm",
            JobOption::ForCandidates => "for_candidates",
            JobOption::Candidates => "candidates",
            JobOption::Tolerances => "tolerance_mm, tolerance_deg",
            JobOption::GravityBoundMrad => "gravity_bound_mrad",
            JobOption::Maps => "maps",
            JobOption::ErrorMotions => "error_motions",
            JobOption::PayloadKg => "payload_kg",
            JobOption::Out => "out",
            JobOption::Bootstrap => "bootstrap",
            JobOption::Robust => "robust",
            JobOption::Nonnegative => "nonnegative",
            JobOption::CrossValidate => "cross_validate",
            JobOption::Folds => "folds",
            JobOption::Offsets => "offsets",
            JobOption::CompareModels => "compare_models",
            JobOption::Seed => "seed",
            JobOption::CalibrationCriterion => "calibration_criterion",
            JobOption::Geometry => "geometry",
            JobOption::Gravity => "gravity",
            JobOption::Weight => "weight",
            JobOption::Restarts => "restarts",
            JobOption::Force => "force",
            JobOption::Level => "level",
            JobOption::Update => "update",
        }
    }
}

/// The text of [`crate::Error::OptionCombination`], each option spelled by `name` (the library and
/// Python by [`JobOption::name`], the command by its flag): `robust: not with nonnegative:
/// REASON`, `seed: only with bootstrap`.
pub fn combination(
    option: &JobOption,
    with: &[JobOption],
    needs: &bool,
    reason: &str,
    name: impl Fn(JobOption) -> String,
) -> String {
    let with: Vec<String> = with.iter().map(|o| name(*o)).collect();
    let mut text = match needs {
        true => format!("{}: only with {}", name(*option), with.join(" and ")),
        false => format!("{}: not with {}", name(*option), with.join(", ")),
    };
    if !reason.is_empty() {
        text += ": ";
        text += reason;
    }
    text
}

impl std::fmt::Display for JobOption {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}
