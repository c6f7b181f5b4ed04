//! How programs are written ([`Settings`]): rapid speeds, name length, moves per file and the
//! limits of each.

use super::Targets;
use stiffid_core::common::error::JobOption;
use stiffid_core::{Error, Result};

/// The default rapid speed ([`Settings::rapid_speed`]) of RAPID's `vrapid`, mm/s, or
/// [`Settings::max_tcp_speed`] when slower.
const RAPID_SPEED_MM_S: f64 = 200.0;
/// The default joint speed of rapid moves ([`Settings::rapid_joint_pct`]: KRL `BAS(#VEL_PTP)`,
/// LS `J`, INFORM `VJ=`), percent of the axes' top speed; KRL's `BAS(#ACC_PTP)` always.
pub(crate) const RAPID_PERCENT: u32 = 20;
/// The slowest feed written, m/s (0.001 mm/s): a slower one is refused, never written as 0.
pub(crate) const MIN_FEED: f64 = 1e-6;
/// The range of [`Settings::moves_per_file`].
pub(crate) const MOVES_PER_FILE: std::ops::RangeInclusive<usize> = 100..=1_000_000;
/// The range of [`Settings::name_length`].
pub(crate) const NAME_LENGTH: std::ops::RangeInclusive<usize> = 8..=64;

/// How programs are written (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// Cartesian or joint targets.
    pub targets: Targets,
    /// Whether `targets` was asked for (an option given, not its default): a language that
    /// writes joint targets only (INFORM) says so only then.
    pub targets_asked: bool,
    /// The robot's largest TCP speed, m/s (> 0, at most 10): a faster feed is refused.
    pub max_tcp_speed: f64,
    /// The longest program name the controller takes; `None`: the dialect's
    /// (`default_name_length`).
    pub name_length: Option<usize>,
    /// The most moves in one program file (100 to 1 000 000).
    pub moves_per_file: usize,
    /// The TCP speed of rapid moves where the language states one (RAPID `vrapid`, at most
    /// `max_tcp_speed`), m/s, within
    /// [`stiffid_core::setup::program_io::RAPID_SPEED_MM_S`] (the setup's `[controller]
    /// rapid_speed_mm_s`).
    pub rapid_speed: f64,
    /// The joint speed of rapid moves (KRL `BAS(#VEL_PTP)`, LS `J .. %`, INFORM `VJ=`), percent
    /// of the axes' top speed, within [`stiffid_core::setup::program_io::RAPID_JOINT_PCT`] (the
    /// setup's `[controller] rapid_joint_pct`); LS states whole percents, INFORM hundredths.
    pub rapid_joint_pct: f64,
    /// The date the written programs state (LS `CREATE`/`MODIFIED`, INFORM `///DATE`), whole
    /// seconds since 1970-01-01 00:00 UTC, 0 to 253 402 300 799 (9999-12-31 23:59:59): the front ends
    /// give `SOURCE_DATE_EPOCH`'s ([`super::date::epoch`]), else 0, so the same input writes
    /// the same bytes.
    pub date_s: i64,
}

impl Default for Settings {
    /// Cartesian targets (not asked), 2000 mm/s, the dialect's name length, 10 000 moves per file,
    /// rapids at 200 mm/s and 20 %, dated 1970-01-01.
    fn default() -> Self {
        Self {
            targets: Targets::Cartesian,
            targets_asked: false,
            max_tcp_speed: 2.0,
            name_length: None,
            moves_per_file: 10_000,
            rapid_speed: RAPID_SPEED_MM_S * 1e-3,
            rapid_joint_pct: RAPID_PERCENT as f64,
            date_s: 0,
        }
    }
}

impl Settings {
    /// Checks every field against its limit.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the option ([`JobOption::MaxTcpSpeedMmS`],
    /// [`JobOption::NameLength`], [`JobOption::MovesPerFile`]), the value and the range;
    /// [`Error::InvalidField`] (`SOURCE_DATE_EPOCH`) for a date outside its range.
    pub fn validate(&self) -> Result<()> {
        let bad = |option, message: String| Err(Error::InvalidOption { option, message });
        if !(self.max_tcp_speed > 0.0 && self.max_tcp_speed <= 10.0) {
            return bad(
                JobOption::MaxTcpSpeedMmS,
                format!(
                    "{} mm/s: expected > 0 and at most 10000",
                    self.max_tcp_speed * 1e3
                ),
            );
        }
        if let Some(n) = self.name_length.filter(|n| !NAME_LENGTH.contains(n)) {
            return bad(
                JobOption::NameLength,
                format!(
                    "{n}: expected {} to {}",
                    NAME_LENGTH.start(),
                    NAME_LENGTH.end()
                ),
            );
        }
        self.validate_rapids()?;
        super::date::epoch(&self.date_s.to_string())?;
        if !MOVES_PER_FILE.contains(&self.moves_per_file) {
            return bad(
                JobOption::MovesPerFile,
                format!(
                    "{}: expected {} to {}",
                    self.moves_per_file,
                    MOVES_PER_FILE.start(),
                    MOVES_PER_FILE.end()
                ),
            );
        }
        Ok(())
    }
}

impl Settings {
    /// Checks the rapid speeds against their ranges.
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming `controller.rapid_speed_mm_s` or
    /// `controller.rapid_joint_pct`.
    fn validate_rapids(&self) -> Result<()> {
        use stiffid_core::common::limits::check;
        use stiffid_core::setup::program_io::{RAPID_JOINT_PCT, RAPID_SPEED_MM_S};
        let mm_s = self.rapid_speed * 1e3;
        check("controller.rapid_speed_mm_s", &[mm_s], &RAPID_SPEED_MM_S)?;
        check(
            "controller.rapid_joint_pct",
            &[self.rapid_joint_pct],
            &RAPID_JOINT_PCT,
        )
    }
}
