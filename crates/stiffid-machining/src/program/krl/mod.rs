//! KUKA KRL: `PTP {A1 0, A2 -90, ...}`, `LIN {...}` (also `SPTP`, `SLIN`, an optional type
//! `{E6AXIS: ...}` and an approximation `C_PTP`, `C_DIS`, `C_VEL`, `C_ORI`, `C_SPL`), or the same
//! to a point declared in the file: `DECL E6AXIS XP1={A1 0,...}` (or `AXIS`, with or without
//! `DECL`, `GLOBAL`, `CONST`); `;` starts a comment. KRL is line based and case-insensitive.
//!
//! The members `E1` to `E6` of an aggregate are the external axes as `$EX_AX_NUM` numbers them
//! (mm for a linear axis, deg for a rotary one): read, and written back where they change.
//!
//! An aggregate or declared point with `X`, `Y`, `Z`, `A`, `B`, `C` (`E6POS`, `POS`, `FRAME`,
//! with `S` and `T`) is a Cartesian target in the `$BASE` and for the `$TOOL` in force at the
//! motion ([`super::cartesian`]): a literal frame, or a frame by number as the inline forms and
//! the BAS package select it (`frames`).
//!
//! As KUKA System Software stores a program: the `.dat` beside the `.src` (same folder and stem,
//! `program::data_beside`) declares its points and frame data (`declare`); inline forms (`;FOLD PTP P1
//! .. Tool[1] Base[2]` with `FDAT_ACT = FP1` and `BAS(#PTP_PARAMS, ..)`, KSS 8's `SPTP .. WITH
//! $TOOL = STOOL2(FP1), ..`) are read from their bodies; `CIRC` gives its auxiliary and end points
//! (`motion`); what is in force at each motion is followed through loops, branches and the
//! routines of the file (`read`, `state`). The guide's
//! page `docs/programs/krl.md` lists each rule with its source.

mod assign;
mod backup;
mod branches;
mod called;
mod calls;
pub(crate) mod cartesian;
pub(crate) mod data;
mod declare;
mod frames;
mod generate;
mod known;
mod motion;
mod names;
mod numbers;
mod operator;
mod process;
mod read;
pub(crate) mod speed;
mod state;
pub(crate) mod status;
mod unroll;
pub use status::{StatusPart, StatusTurn};

use super::controller::{BoundComment, Controller, Generator, Read};
use super::descriptor::{AxisNames, Descriptor, FileName, NameRules};
use super::generate::zyx_deg;
use nalgebra::{UnitQuaternion, Vector3};
use stiffid_core::Result;

/// KUKA KRL (module docs).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Krl;

impl Controller for Krl {
    type Flags = StatusTurn;
    const LANGUAGE: &'static Descriptor = &Descriptor {
        key: "krl",
        title: "KUKA KRL",
        extensions: &["src", "dat"],
        data_files: &[(
            "dat",
            "a KRL program (DEF) is written to a .src file; its .dat holds only data (DEFDAT)",
        )],
        motions: "PTP or LIN to {A1 .., A6 ..} or {X .., .., C .., S .., T ..}, or to an E6AXIS or E6POS declared in the file; a .dat holds declarations only: give the .src",
        joint_forms: "E6AXIS, AXIS",
        part_forms: Some("E6POS with $BASE equal to [workpiece]"),
        external_axes: AxisNames::Numbered("E"),
        unused_axis: "",
        zero_is_no_axis: true,
        names: NameRules {
            declared_by: Some("DEF"),
            file: FileName::Stem,
            max_length: 24,
            default_length: 24,
            reserved: names::RESERVED,
        },
        bound_comment: BoundComment::EndOfLine {
            marker: ';',
            statement: None,
        },
        motion_words: &["PTP ", "LIN ", "CIRC "],
        frame_numbers: (16, 32),
        axis_3_from_horizontal: false,
    };

    fn read(&self, text: &str) -> Result<Read> {
        self.read_in(text, &super::Context::default())
    }
    fn read_in(&self, text: &str, context: &super::Context) -> Result<Read> {
        read::targets(text, context)
    }
    fn rotation(&self, n: &[f64]) -> UnitQuaternion<f64> {
        abc(n[3], n[4], n[5])
    }
    fn pose_numbers(&self, p: &Vector3<f64>, r: &UnitQuaternion<f64>) -> Vec<f64> {
        let [a, b, c] = zyx_deg(r);
        vec![p.x, p.y, p.z, a, b, c]
    }
    /// `DEF` after an optional `GLOBAL`, in any case, followed by a blank.
    fn declares_name(&self, line: &str) -> Option<usize> {
        let upper = line.to_ascii_uppercase();
        let rest = upper
            .strip_prefix("GLOBAL")
            .map_or(upper.as_str(), str::trim_start);
        rest.strip_prefix("DEF")
            .filter(|r| r.starts_with(char::is_whitespace))
            .map(|r| line.len() - r.len())
    }
    fn generator(&self) -> Option<&'static dyn Generator> {
        Some(&Krl)
    }
    /// A KUKA backup's modules (`.src`, `.dat`: `$config.dat`, the module's data list).
    fn backup_extensions(&self) -> &'static [&'static str] {
        &["src", "dat"]
    }
    /// Every module and data list but the system's own `$` files other than `$config.dat` (a
    /// KSS backup holds `$machine.dat` of the controller and of the robot, say).
    fn held_once(&self, name: &str) -> bool {
        !name.starts_with('$') || name.eq_ignore_ascii_case("$config.dat")
    }
    /// The module's `.dat` in the backup: the file named after the `.src`'s first `DEF` (KSS
    /// names a module's two files and its routine alike), `.dat` in any case.
    fn data_file<'a>(&self, text: &str, context: &super::Context<'a>) -> Option<&'a str> {
        let name = (text.lines()).find_map(|l| {
            Controller::declares_name(self, l.trim_start())
                .map(|at| l.trim_start()[at..].to_string())
        })?;
        let name = name.trim_start().split(['(', ' ']).next()?.to_string();
        let file = format!("{name}.dat");
        context.backup_file(&file).map(|(_, t)| t)
    }
}

/// A rotation from KUKA's A, B, C (deg): `R = Rz(A) Ry(B) Rx(C)`.
fn abc(a: f64, b: f64, c: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_euler_angles(c.to_radians(), b.to_radians(), a.to_radians())
}

#[cfg(test)]
mod cartesian_tests;

#[cfg(test)]
mod corpus_tests;
