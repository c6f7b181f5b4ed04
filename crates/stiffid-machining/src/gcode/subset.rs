//! The G-code subset read, and the error for a code outside it (saying why for those real
//! posts write).

use super::at;

pub(super) const SUBSET: &str = "G0-G4, G5.1 (linuxcnc), G10 L2, G10 L20, G17-G21, G28, G30, G40-G42, G43, G44, G49, G53-G59.3, G54.1, G61, G61.1, G64, G80-G83, G90, G90.1, G91, G91.1, G68 G69 (fanuc, haas), G92 (linuxcnc, grbl), G92.1, G92.2, G94, G98, G99";

/// The error for a `G` code outside the subset, saying why for those real posts write.
pub(super) fn unsupported(line: u64, g: &str) -> stiffid_core::Error {
    let why = match g {
        "G92.3" => ": it restores an offset from the controller's parameters, which stiffid cannot know; give the work offsets in the setup ([workpiece.offsets])",
        "G93" | "G95" => ": the feed rate F would be per block (G93) or per revolution (G95); post the program in G94 (per minute)",
        "G28.1" | "G30.1" => ": it stores the machine's position at run time as the home position; give it in the setup ([workpiece] g28_mm, g30_mm)",
        "G51" | "G50.1" | "G51.1" | "G15" | "G16" => ": a scaling, mirror or polar mode the path would pass through",
        _ => "",
    };
    at(
        line,
        format!("{g}: not in the supported subset ({SUBSET}){why}"),
    )
}
