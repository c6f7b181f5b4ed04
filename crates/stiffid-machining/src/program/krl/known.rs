//! The numbers a KRL program reads where it reads them ([`super::numbers`]): assigned on the
//! path read, or declared with a value in the files; an assignment of one computed where every
//! value it reads is known.

use super::assign::{Value, Values, Writer};
use super::declare::Declarations;
use super::numbers::{evaluate, Typed};
use stiffid_core::common::limits::short;

/// The number `name` (upper case) where routine `routine` reads it: assigned on the path read
/// (`values`), or declared with a value (`declared`).
pub(super) fn number(
    d: &Declarations,
    name: &str,
    routine: usize,
    values: &Values,
) -> Result<Typed, String> {
    match values.get(name) {
        Some(Value::Number(_, v, int)) => return Ok((*v, *int)),
        Some(Value::Assigned(l)) => {
            return Err(format!(
                "{name} holds the value a previous run left (it is assigned on line {l})"
            ))
        }
        Some(Value::Unknown(w)) => return Err(format!("{name} {w}")),
        Some(Value::Known(..)) => return Err(format!("{name} is a point, not a number")),
        None => {}
    }
    let local = routine.checked_sub(2).and_then(|k| d.local_nums.get(k));
    if local.is_some_and(|l| l.contains(name)) {
        return Err(format!(
            "{name} is declared in its routine without a value (set at run time)"
        ));
    }
    match d.nums.get(name) {
        Some((_, v)) => v.clone(),
        None => Err(format!("{name} is no number declared with a value in the .src, its .dat or a global data list (REAL, INT, BOOL)")),
    }
}

impl Writer<'_> {
    /// The number `name` (upper case) where routine `routine` reads it ([`number`]).
    pub(super) fn number(
        &self,
        name: &str,
        routine: usize,
        values: &Values,
    ) -> Result<Typed, String> {
        number(self.declared, name, routine, values)
    }

    /// The value of `text` read in `routine` with `values` ([`evaluate`]).
    pub(super) fn evaluate(
        &self,
        text: &str,
        routine: usize,
        values: &Values,
    ) -> Result<Typed, String> {
        let lookup = |n: &str| Some(self.number(&n.to_ascii_uppercase(), routine, values));
        evaluate(text, &lookup)
    }

    /// The number `name` assigned `rhs` on `line`: its value, or unknown naming the line.
    pub(super) fn number_assigned(
        &self,
        line: u64,
        name: &str,
        rhs: &str,
        routine: usize,
        values: &Values,
    ) -> Value {
        let int = self.declared.num_types.get(name).copied().unwrap_or(false);
        match self.evaluate(rhs, routine, values) {
            Ok((v, _)) if int && v.fract() != 0.0 => Value::Unknown(format!("is assigned on line {line} a REAL value ({v}) that the controller rounds to an INT: write the value as an INT")),
            Ok((v, _)) => Value::Number(line, v, int),
            Err(why) => Value::Unknown(format!("is assigned on line {line} from '{}' ({why}), so its value is the run's, not the file's", short(rhs.trim()))),
        }
    }
}
