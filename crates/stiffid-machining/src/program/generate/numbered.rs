//! The tool and base a generated program selects by number: the frames the controller holds in
//! its tables (the setup's `[controller] tools` and `bases`,
//! [`stiffid_core::setup::NumberedFrames`]) that are the program's tool and part frame.
//!
//! A table's frame is the program's when it lies within 0.001 mm and 0.001 deg of it: the values a
//! user copies from the pendant into the setup, to its decimals. Then the program selects it by
//! number instead of stating it (KRL `$TOOL = TOOL_DATA[n]`, `$BASE = BASE_DATA[m]`; LS
//! `UTOOL_NUM=n`, `UFRAME_NUM=m`, positions `UT : n`, `UF : m` in user frame `m`; INFORM tool file
//! `n`, `///TOOL n`), as a teach pendant writes it. Numbers from 1: number 0 is the flange or the
//! world on every controller (and no `TOOL_DATA[0]` exists); of several matching frames the lowest
//! number is taken. A program with no matching frame states it as before (KRL `$TOOL = {..}`, LS
//! user frame 0; LS and INFORM select the lowest tool number from 1 the table holds no frame in,
//! with its values in remarks or comments, and refuse when it holds another tool in all of 1 to
//! 10).

use nalgebra::Isometry3;
use stiffid_core::setup::NumberedFrames;
use stiffid_core::{Error, Result};

/// How far (mm) a table's frame may lie from the program's tool or part frame and be taken.
pub(crate) const MATCH_MM: f64 = 0.001;
/// How far (deg) a table's frame may turn from the program's tool or part frame and be taken.
pub(crate) const MATCH_DEG: f64 = 0.001;

/// The program's tool and part frame as the controller holds them by number, with the table's
/// frame (lengths in m; the tool in the controller's flange frame, the base in its world).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Numbers {
    /// The tool's number and the table's frame.
    pub tool: Option<(u32, Isometry3<f64>)>,
    /// The part frame's (base, user frame) number and the table's frame.
    pub base: Option<(u32, Isometry3<f64>)>,
    /// The tool numbers 1 to 10 the setup's table holds a frame in, bit `n - 1` for number `n`:
    /// what a program whose tool the table does not hold must not select (LS, INFORM).
    pub held_tools: u16,
}

/// The tool numbers a program whose tool the controller's table does not hold may select, from
/// 1: FANUC's ten tool frames (INFORM's tool files go further).
const FREE_TOOLS: u32 = 10;

impl Numbers {
    /// The numbers of `tool` (controller's flange frame) in `tools` and of `base` (the part
    /// frame in the controller's world) in `bases` (module docs), up to the language's highest
    /// tool and base numbers `highest` ([`crate::program::Descriptor::frame_numbers`]).
    pub fn of(
        (tools, bases): (&NumberedFrames, &NumberedFrames),
        tool: &Isometry3<f64>,
        base: &Isometry3<f64>,
        highest: (u32, u32),
    ) -> Self {
        let held = (1..=FREE_TOOLS).filter(|&n| tools.get(n).is_some());
        Self {
            tool: find(tools, tool).filter(|(n, _)| *n <= highest.0),
            base: find(bases, base).filter(|(n, _)| *n <= highest.1),
            held_tools: held.fold(0, |bits, n| bits | 1 << (n - 1)),
        }
    }

    /// The tool number a program selects (LS `UTOOL_NUM`, INFORM `///TOOL`): the table's
    /// number of its tool, else the lowest from 1 the table holds no frame in (a number holding
    /// another tool would send another tool's tip along the path).
    ///
    /// # Errors
    /// [`Error::InvalidField`] (`controller.tools`) when the table holds another tool in every
    /// number from 1 to 10.
    pub(crate) fn tool_number(&self) -> Result<u32> {
        if let Some((n, _)) = self.tool {
            return Ok(n);
        }
        (1..=FREE_TOOLS)
            .find(|n| self.held_tools & 1 << (n - 1) == 0)
            .ok_or_else(|| Error::InvalidField {
                field: "controller.tools".into(),
                message: format!(
                    "every tool number from 1 to {FREE_TOOLS} holds another tool than the \
                     setup's, and the program selects its tool by number: give the setup's tool \
                     as one of them, or leave a number free"
                ),
            })
    }
}

/// The lowest number from 1 of a frame of `table` within the match of `frame`.
fn find(table: &NumberedFrames, frame: &Isometry3<f64>) -> Option<(u32, Isometry3<f64>)> {
    (table.numbers().filter(|n| *n >= 1))
        .filter_map(|n| table.get(n).map(|f| (n, *f)))
        .find(|(_, f)| {
            (f.translation.vector - frame.translation.vector).norm() <= MATCH_MM * 1e-3
                && f.rotation.angle_to(&frame.rotation) <= MATCH_DEG.to_radians()
        })
}
