//! KUKA KRL's process instructions (KUKA System Software 8 manual, "Programming for system
//! integrators": subprogram calls `NAME(..)`, outputs `$OUT[n]=TRUE`, a `SIGNAL` declared in
//! `$CONFIG.DAT` set by its name, comments after `;`).

use crate::program::generate::ProcessForm;
use stiffid_core::setup::program_io::Signal;

/// KRL's forms.
pub(crate) static FORM: ProcessForm = ProcessForm {
    comment: ("; ", ""),
    comment_length: None,
    comment_forbidden: "",
    indent: "",
    call,
    output,
    wait,
};

/// `NAME(a, b)`, `NAME( )` without arguments.
fn call(name: &str, arguments: &[String]) -> Result<String, String> {
    Ok(match arguments.is_empty() {
        true => format!("{name}( )"),
        false => format!("{name}({})", arguments.join(", ")),
    })
}

/// `$OUT[3]=TRUE`, or a declared signal `NAME=FALSE`.
fn output(signal: &Signal, on: bool) -> Result<String, String> {
    let state = if on { "TRUE" } else { "FALSE" };
    Ok(match signal {
        Signal::Number(n) => format!("$OUT[{n}]={state}"),
        Signal::Name(name) => format!("{name}={state}"),
    })
}

/// `WAIT SEC 2.5`: the advance run stops until the time is over (KRL's wait, KUKA System
/// Software 8 manual, "WAIT SEC").
fn wait(seconds: f64) -> String {
    format!("WAIT SEC {}", crate::program::generate::number(seconds))
}
