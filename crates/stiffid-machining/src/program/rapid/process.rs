//! ABB RAPID's process instructions (RAPID Instructions, Functions and Data types: a procedure
//! call `NAME a, b;`, `SetDO signal, value;` on a named digital output, comments after `!`).

use crate::program::generate::ProcessForm;
use stiffid_core::setup::program_io::Signal;

/// RAPID's forms.
pub(crate) static FORM: ProcessForm = ProcessForm {
    comment: ("! ", ""),
    comment_length: None,
    comment_forbidden: "",
    indent: "    ",
    call,
    output,
    wait,
};

/// `NAME;`, `NAME a, b;`.
fn call(name: &str, arguments: &[String]) -> Result<String, String> {
    Ok(match arguments.is_empty() {
        true => format!("{name};"),
        false => format!("{name} {};", arguments.join(", ")),
    })
}

/// `SetDO doSpindle, 1;`: a RAPID output is a named signal.
fn output(signal: &Signal, on: bool) -> Result<String, String> {
    match signal {
        Signal::Name(name) => Ok(format!("SetDO {name}, {};", u8::from(on))),
        Signal::Number(n) => Err(format!("out[{n}]: a RAPID digital output is a named signal (SetDO signal, value): name it, out[doName] = on")),
    }
}

/// `WaitTime 2.5;` (RAPID's wait, ABB Technical reference manual RAPID Instructions,
/// "WaitTime"; the robot stands still at a fine point before it).
fn wait(seconds: f64) -> String {
    format!(
        "WaitTime \\InPos, {};",
        crate::program::generate::number(seconds)
    )
}
