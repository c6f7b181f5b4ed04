//! The parameters (variables) of a program expanded: which numbers exist on the controller,
//! which are local to a call, and which only the controller knows at run time (refused).
//! - LinuxCNC (manual, "Parameters"): `#1`-`#30` local to an `O.. call` (its arguments, 0 when
//!   not given), `#31`-`#5000` global; `#5001` on are the controller's (probing results
//!   `#5061`.., work offsets `#5221`.., the tool in use `#5400`..): refused. Named parameters
//!   `#<name>` are local to the call they are set in, `#<_name>` global; the predefined
//!   `#<_x>`.. are the controller's (refused, as any name read before it is set).
//! - FANUC macro B and Haas: `#1`-`#33` local to a `G65` call (its arguments `A`=`#1`,
//!   `B`=`#2`, ...; an `M98` subprogram shares its caller's), `#100`-`#999` common; `#1000`
//!   on are system variables (refused); `#0` and an argument not given are vacant (refused when
//!   read).
//! - Without a dialect: `#1`-`#30` local, `#31`-`#999` common; `#1000` on refused.
//!
//! A parameter read before the program sets it is refused: its value would be whatever the
//! controller holds from before (LinuxCNC keeps parameters between runs; FANUC's `#500`-`#999`
//! survive power-off).

use super::expr::{Flavour, Param, Values};
use std::collections::HashMap;

/// The parameters' values: the global ones and one set of locals per call.
pub(super) struct Store {
    flavour: Flavour,
    global: HashMap<u32, f64>,
    named_global: HashMap<String, f64>,
    locals: Vec<Locals>,
}

#[derive(Default)]
struct Locals {
    numbered: HashMap<u32, f64>,
    named: HashMap<String, f64>,
    /// A call's level (`O.. call`, `G65`): unset numbered locals are 0 on LinuxCNC.
    called: bool,
}

impl Store {
    pub(super) fn new(flavour: Flavour) -> Self {
        Store {
            flavour,
            global: HashMap::new(),
            named_global: HashMap::new(),
            locals: vec![Locals::default()],
        }
    }

    /// The highest local number.
    fn local_max(&self) -> u32 {
        match self.flavour {
            Flavour::Fanuc => 33,
            _ => 30,
        }
    }

    /// Why `n` is not a parameter the program may use, if it is not.
    fn refused(&self, n: u32) -> Option<String> {
        let system = match self.flavour {
            Flavour::LinuxCnc => 5001,
            _ => 1000,
        };
        if n >= system {
            return Some(format!("#{n}: a parameter the controller sets at run time or holds in its tables (from #{system} on: probing results, work offsets, the tool table, positions); stiffid cannot know its value"));
        }
        if n == 0 || (self.flavour == Flavour::Fanuc && (34..100).contains(&n)) {
            return Some(format!("#{n}: no such variable here (FANUC and Haas: #0 is vacant, #1-#33 local, #100-#999 common)"));
        }
        None
    }

    /// A new level of locals for a call (`O.. call`, `G65`) with its arguments.
    pub(super) fn push(&mut self, args: &[(u32, f64)]) {
        let mut l = Locals {
            called: true,
            ..Default::default()
        };
        l.numbered.extend(args.iter().copied());
        self.locals.push(l);
    }

    /// The call's locals dropped.
    pub(super) fn pop(&mut self) {
        if self.locals.len() > 1 {
            self.locals.pop();
        }
    }

    /// `p = value`.
    pub(super) fn set(&mut self, p: &Param, value: f64) -> Result<(), String> {
        match p {
            Param::Number(n) => {
                if let Some(why) = self.refused(*n) {
                    return Err(format!("{why}; setting it changes the controller's state"));
                }
                if *n <= self.local_max() {
                    self.top().numbered.insert(*n, value);
                } else {
                    self.global.insert(*n, value);
                }
            }
            Param::Named(name) => {
                self.named(name)?;
                if name.starts_with('_') {
                    self.named_global.insert(name.clone(), value);
                } else {
                    self.top().named.insert(name.clone(), value);
                }
            }
        }
        Ok(())
    }

    fn top(&mut self) -> &mut Locals {
        let last = self.locals.len() - 1;
        &mut self.locals[last]
    }

    fn named(&self, name: &str) -> Result<(), String> {
        match self.flavour {
            Flavour::Fanuc => Err(format!(
                "#<{name}>: a named parameter (LinuxCNC's), not FANUC's or Haas's macro variables"
            )),
            _ => Ok(()),
        }
    }
}

impl Values for Store {
    fn value(&self, p: &Param) -> Result<f64, String> {
        let top = &self.locals[self.locals.len() - 1];
        match p {
            Param::Number(n) => {
                if let Some(why) = self.refused(*n) {
                    return Err(why);
                }
                let local = *n <= self.local_max();
                let found = match local {
                    true => top.numbered.get(n),
                    false => self.global.get(n),
                };
                match (found, local && top.called) {
                    (Some(v), _) => Ok(*v),
                    (None, true) if self.flavour == Flavour::LinuxCnc => Ok(0.0),
                    (None, true) => Err(format!("#{n}: vacant (not given in the call)")),
                    (None, false) => Err(unset(&p.to_string())),
                }
            }
            Param::Named(name) => {
                self.named(name)?;
                let found = match name.starts_with('_') {
                    true => self.named_global.get(name),
                    false => top.named.get(name),
                };
                found.copied().ok_or_else(|| unset(&p.to_string()))
            }
        }
    }
}

fn unset(p: &str) -> String {
    format!("{p} is read before the program sets it: its value is whatever the controller holds (a parameter from an earlier run, one the controller sets); set it in the program")
}
