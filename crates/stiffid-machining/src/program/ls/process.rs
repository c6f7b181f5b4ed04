//! FANUC LS's process instructions (FANUC R-30iB Operator's Manual: `CALL NAME ;` and
//! `CALL NAME(arg, ..) ;` with arguments, `DO[n]=ON ;`, a remark `! .. ;` of at most 32
//! characters).

use crate::program::generate::ProcessForm;
use stiffid_core::setup::program_io::Signal;

/// LS's forms.
pub(crate) static FORM: ProcessForm = ProcessForm {
    comment: ("! ", " ;"),
    comment_length: Some(32),
    comment_forbidden: ";",
    indent: "",
    call,
    output,
    wait,
};

/// `CALL NAME ;`, `CALL NAME(a,b) ;`.
fn call(name: &str, arguments: &[String]) -> Result<String, String> {
    Ok(match arguments.is_empty() {
        true => format!("CALL {name} ;"),
        false => format!("CALL {name}({}) ;", arguments.join(",")),
    })
}

/// `DO[3]=ON ;`: an LS program sets outputs by number.
fn output(signal: &Signal, on: bool) -> Result<String, String> {
    match signal {
        Signal::Number(n) => Ok(format!("DO[{n}]={} ;", if on { "ON" } else { "OFF" })),
        Signal::Name(name) => Err(format!("out[{name}]: an LS program sets a digital output by its number, DO[n]: give out[n] = on")),
    }
}

/// `WAIT 2.50(sec) ;` (LS's wait instruction, FANUC R-30iB Operator's Manual, "WAIT
/// instruction": a time in steps of 0.01 s).
fn wait(seconds: f64) -> String {
    format!("WAIT {:.2}(sec) ;", seconds)
}
