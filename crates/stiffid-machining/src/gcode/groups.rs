//! The modal groups of the `G` and `M` codes (RS274/NGC, LinuxCNC's manual "Modal Groups";
//! Fanuc's G-code groups): a block sets each group once. Two codes of one group in a block
//! (`G90 G91`, `G17 G18`, `G0 G1`, `M3 M4`) are an error on LinuxCNC and one of them, which the
//! control decides, on others: the block is refused naming the line, never read as the last one.
//! `M7` and `M8` (mist and flood) may go together; `M9` with either may not. `G80` (cycle off)
//! goes with a motion, as safety lines write it (`G0 G17 G40 G49 G80 G90`), and the path control
//! codes (`G61`, `G61.1`, `G64`: how the controller blends the corners, not where the points
//! are) are not checked, as posts write them together (`G61 G64 P0.01`).

use super::at;
use super::words::Word;
use stiffid_core::common::words::number;
use stiffid_core::Result;

/// The modal group of the code `letter value` (its name for messages), `None` for a code that
/// is in none of them (or is refused elsewhere).
fn group(letter: char, value: f64) -> Option<&'static str> {
    let tenths = (value * 10.0).round();
    if (value * 10.0 - tenths).abs() > 1e-6 || !(0.0..10_000.0).contains(&tenths) {
        return None;
    }
    let name = match (letter, tenths as u16) {
        ('G', 0 | 10 | 20 | 30 | 51 | 810 | 820 | 830) => "motion (G0-G3, G81-G83)",
        ('G', 170 | 180 | 190) => "plane (G17-G19)",
        ('G', 900 | 910) => "distance mode (G90, G91)",
        ('G', 901 | 911) => "arc centre mode (G90.1, G91.1)",
        ('G', 930 | 940 | 950) => "feed rate mode (G93-G95)",
        ('G', 200 | 210) => "units (G20, G21)",
        ('G', 400 | 410 | 420) => "cutter compensation (G40-G42)",
        ('G', 430 | 440 | 490) => "tool length offset (G43, G44, G49)",
        ('G', 980 | 990) => "cycle return (G98, G99)",
        ('G', 540 | 550 | 560 | 570 | 580 | 590 | 541 | 591..=593) => "work offset (G54-G59.3)",
        ('M', 0 | 10 | 20 | 300 | 600) => "stop (M0, M1, M2, M30, M60)",
        ('M', 30 | 40 | 50) => "spindle (M3-M5)",
        ('M', 70 | 80) => "coolant on (M7, M8)",
        ('M', 90) => "coolant off (M9)",
        _ => return None,
    };
    Some(name)
}

/// `Err` naming `line` where two of `words` set one modal group (module docs).
pub(super) fn one_per_group(line: u64, words: &[Word]) -> Result<()> {
    let mut seen: Vec<(&'static str, &Word)> = Vec::new();
    for w in words.iter().filter(|w| matches!(w.letter, 'G' | 'M')) {
        let Some(name) = group(w.letter, w.value) else {
            continue;
        };
        let clash = |n: &str| match name {
            "coolant on (M7, M8)" => n == "coolant off (M9)",
            "coolant off (M9)" => n == "coolant on (M7, M8)" || n == name,
            _ => n == name,
        };
        if let Some((_, first)) = seen.iter().find(|(n, _)| clash(n)) {
            return Err(at(
                line,
                format!(
                    "{}{}: a second code of the {name} group in one block ({}{} before it): a controller refuses it or runs one of them, which the program does not say; give one per block",
                    w.letter,
                    number(w.value),
                    first.letter,
                    number(first.value)
                ),
            ));
        }
        seen.push((name, w));
    }
    Ok(())
}
