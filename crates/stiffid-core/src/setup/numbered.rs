//! Frames a robot controller holds by number, which a program selects without stating them: tools
//! (KUKA `TOOL_DATA[n]`, FANUC `UTOOL[n]`, a Yaskawa tool file) and bases (KUKA `BASE_DATA[n]`,
//! FANUC `UFRAME[n]`, a Yaskawa user frame), as the setup's `[controller] tools` and `bases`
//! tables give them ([`super::Controller::tools`], [`super::Controller::bases`]).
//!
//! ```toml
//! [controller]
//! tools = [{ number = 1, xyz_mm = [0, 0, 250], rpy_deg = [0, 0, 0] }]
//! bases = [{ number = 2, xyz_mm = [1200, -300, 400], rpy_deg = [0, 0, 90] }]
//! ```
//!
//! A tool is given in the controller's flange frame, a base in the controller's world frame
//! (module docs of `setup::workcell`), as the controller's own tables hold them. Numbers run
//! from 0 to `MAX_FRAME_NUMBER`; what a number the table lacks means (the flange, the world, or
//! a frame stiffid cannot know) is each language's rule.

use crate::common::limits::{self, check_count};
use crate::robot::file::TransformFile;
use crate::{Error, Result};
use nalgebra::Isometry3;
use serde::Deserialize;
use std::collections::BTreeMap;

/// The largest frame number of a table (`number`, from 0): every controller's tables are
/// smaller (KUKA 16 tools and 32 bases, FANUC 10 tools and 9 user frames, Yaskawa 64 tools).
pub(crate) const MAX_FRAME_NUMBER: u32 = 999;

/// A table of frames by number (module docs), lengths in m.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NumberedFrames {
    frames: BTreeMap<u32, Isometry3<f64>>,
}

impl NumberedFrames {
    /// The frame numbered `number`, if the table gives it.
    pub fn get(&self, number: u32) -> Option<&Isometry3<f64>> {
        self.frames.get(&number)
    }

    /// The numbers the table gives, ascending.
    pub fn numbers(&self) -> impl Iterator<Item = u32> + '_ {
        self.frames.keys().copied()
    }

    /// A table of `frames` (number, frame); `field` names it in errors (`controller.tools`).
    ///
    /// # Errors
    /// [`Error::InvalidField`] naming `field[i].number` for a number above
    /// `MAX_FRAME_NUMBER` or given twice, or `field` for more than `MAX_FRAME_NUMBER + 1`
    /// frames.
    pub fn new(field: &str, frames: &[(u32, Isometry3<f64>)]) -> Result<Self> {
        check_count(field, frames.len(), 0, MAX_FRAME_NUMBER as usize + 1)?;
        let mut table = BTreeMap::new();
        for (i, (number, frame)) in frames.iter().enumerate() {
            let here = format!("{field}[{}].number", i + 1);
            if *number > MAX_FRAME_NUMBER {
                return Err(Error::InvalidField {
                    field: here,
                    message: format!(
                        "{number}: expected a frame number from 0 to {MAX_FRAME_NUMBER}"
                    ),
                });
            }
            if table.insert(*number, *frame).is_some() {
                let first = frames.iter().position(|(n, _)| n == number).unwrap_or(0);
                return Err(Error::InvalidField {
                    field: here,
                    message: format!(
                        "{number} is given twice (entries {} and {}): one frame per number",
                        first + 1,
                        i + 1
                    ),
                });
            }
        }
        Ok(Self { frames: table })
    }
}

/// One entry of a `[controller] tools` or `bases` table as the file gives it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct NumberedFrameFile {
    number: i64,
    #[serde(default, deserialize_with = "crate::common::exact::array")]
    xyz_mm: [f64; 3],
    #[serde(default, deserialize_with = "crate::common::exact::array")]
    rpy_deg: [f64; 3],
}

/// The table `field` (`controller.tools`) of the file's `entries`, each checked.
///
/// # Errors
/// [`Error::InvalidField`] naming `field[i].number` (negative, above `MAX_FRAME_NUMBER` or
/// given twice), `field[i].xyz_mm` or `field[i].rpy_deg` (outside [`limits::LENGTH_MM`] or
/// [`limits::ANGLE_DEG`]), or `field` (too many entries).
pub(super) fn read(field: &str, entries: &[NumberedFrameFile]) -> Result<NumberedFrames> {
    check_count(field, entries.len(), 0, MAX_FRAME_NUMBER as usize + 1)?;
    let mut frames = Vec::with_capacity(entries.len());
    for (i, e) in entries.iter().enumerate() {
        let here = format!("{field}[{}]", i + 1);
        let number = u32::try_from(e.number)
            .ok()
            .filter(|n| *n <= MAX_FRAME_NUMBER)
            .ok_or_else(|| Error::InvalidField {
                field: format!("{here}.number"),
                message: format!(
                    "{}: expected a frame number from 0 to {MAX_FRAME_NUMBER}",
                    e.number
                ),
            })?;
        limits::check(&format!("{here}.xyz_mm"), &e.xyz_mm, &limits::LENGTH_MM)?;
        limits::check(&format!("{here}.rpy_deg"), &e.rpy_deg, &limits::ANGLE_DEG)?;
        let t = TransformFile {
            xyz_mm: e.xyz_mm,
            rpy_deg: e.rpy_deg,
        };
        frames.push((number, t.isometry()));
    }
    NumberedFrames::new(field, &frames)
}
