//! Yaskawa INFORM's process instructions (DX200 / YRC1000 INFORM manual: `CALL JOB:NAME`,
//! `DOUT OT#(n) ON`, a comment line `'..` of at most 32 characters, its `'` included).

use crate::program::generate::ProcessForm;
use stiffid_core::setup::program_io::Signal;

/// INFORM's forms.
pub(crate) static FORM: ProcessForm = ProcessForm {
    comment: ("'", ""),
    comment_length: Some(31),
    comment_forbidden: "",
    indent: "",
    call,
    output,
    wait,
};

/// `CALL JOB:NAME`; a call with arguments is refused.
fn call(name: &str, arguments: &[String]) -> Result<String, String> {
    match arguments.is_empty() {
        true => Ok(format!("CALL JOB:{name}")),
        false => Err(format!("{name}: stiffid writes an INFORM CALL JOB without arguments (INFORM passes a call's arguments, read with GETARG, only where the controller has argument passing, in a form stiffid does not write); map the event to a job that takes none, e.g. \"{name}\", which reads the value from a variable set on the controller, or to an output out[n] = on")),
    }
}

/// `DOUT OT#(3) ON`: a job sets outputs by number.
fn output(signal: &Signal, on: bool) -> Result<String, String> {
    match signal {
        Signal::Number(n) => Ok(format!("DOUT OT#({n}) {}", if on { "ON" } else { "OFF" })),
        Signal::Name(name) => Err(format!("out[{name}]: an INFORM job sets a general output by its number, DOUT OT#(n): give out[n] = on")),
    }
}

/// `TIMER T=2.50` (INFORM's timer instruction, DX200 / YRC1000 INFORM manual, "TIMER": a time
/// in steps of 0.01 s, at most 655.35 s).
fn wait(seconds: f64) -> String {
    format!("TIMER T={:.2}", seconds)
}
