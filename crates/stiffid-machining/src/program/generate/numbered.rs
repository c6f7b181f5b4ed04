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
//! user frame 0 and tool frame 1 with its values in remarks).

use nalgebra::Isometry3;
use stiffid_core::setup::NumberedFrames;

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
}

impl Numbers {
    /// The numbers of `tool` (controller's flange frame) in `tools` and of `base` (the part
    /// frame in the controller's world) in `bases` (module docs).
    pub fn of(
        (tools, bases): (&NumberedFrames, &NumberedFrames),
        tool: &Isometry3<f64>,
        base: &Isometry3<f64>,
    ) -> Self {
        Self {
            tool: find(tools, tool),
            base: find(bases, base),
        }
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
