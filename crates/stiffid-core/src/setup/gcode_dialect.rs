//! `[controller] dialect`: which controller runs a G-code program, where controllers read the
//! same words differently (when a tool length offset `G43` made without a move takes effect and
//! what `G91` after it counts from, `G53` under `G91`, whether `G28` cancels the tool length
//! offset). The rules per dialect are the G-code reader's (`stiffid_machining::gcode`,
//! docs/programs/gcode.md).

/// The controller a G-code program is written for (`[controller] dialect`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GcodeDialect {
    /// LinuxCNC's interpreter (rs274ngc).
    LinuxCnc,
    /// FANUC (Series 0i, 30i and their kin).
    Fanuc,
    /// Haas (the NGC and classic controls).
    Haas,
    /// grbl (1.1).
    Grbl,
}

impl crate::common::choice::Choice for GcodeDialect {
    const FIELD: &'static str = "controller.dialect";
    const ALL: &'static [Self] = &[
        GcodeDialect::LinuxCnc,
        GcodeDialect::Fanuc,
        GcodeDialect::Haas,
        GcodeDialect::Grbl,
    ];
    fn name(self) -> &'static str {
        match self {
            GcodeDialect::LinuxCnc => "linuxcnc",
            GcodeDialect::Fanuc => "fanuc",
            GcodeDialect::Haas => "haas",
            GcodeDialect::Grbl => "grbl",
        }
    }
    fn help(self) -> &'static str {
        match self {
            GcodeDialect::LinuxCnc => {
                "LinuxCNC's interpreter: G43 re-expresses where the tool is, G91 counts from there"
            }
            GcodeDialect::Fanuc => {
                "FANUC: G43 shifts the end point of the next Z move, in G90 and G91 alike"
            }
            GcodeDialect::Haas => "Haas: as FANUC, and G28 cancels the tool length offset",
            GcodeDialect::Grbl => {
                "grbl 1.1: no tool table (G43 H refused), G53 in G91 absolute as LinuxCNC"
            }
        }
    }
}

crate::common::choice::by_name!(GcodeDialect);
