//! What the reading of a RAPID module carries from statement to statement and from a call into
//! the routine it reads (module `read`): the configuration monitoring and the values of the
//! points and `num` data the module assigns in force, joined where paths meet; a call's entry
//! into the routine; what a module read gives.

use super::assign::Bound;
use super::called::Bindings;
use super::numflow;
use super::place::Place;
use super::Statement;
use crate::program::paths::Join;
use crate::program::{JointTarget, Left};

/// Configuration monitoring in force for joint (0) and linear (1) motions: off (`\Off`), on, or
/// why the file does not say; and the values of the points the module assigns (module `assign`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Conf(
    pub(super) [std::result::Result<bool, String>; 2],
    pub(super) Bound,
    pub(super) numflow::Values,
);

impl Join for Conf {
    fn join(&mut self, other: &Self, (word, line): (&str, u64)) {
        for k in 0..2 {
            if self.0[k] != other.0[k] && self.0[k].is_ok() {
                let name = ["ConfJ", "ConfL"][k];
                self.0[k] = match &other.0[k] {
                    Err(why) => Err(why.clone()),
                    Ok(_) => Err(format!("{name} \\Off is in force on one path through {word} (line {line}) only: the controller holds this motion to its confdata on one path and not on the other; set {name} alike on every path, or before {word}")),
                };
            }
        }
        for (name, other) in &other.1 {
            match self.1.get_mut(name) {
                Some(mine) if mine == other => {}
                Some(mine) => {
                    mine.target = Err(format!("{name} is assigned differently on the paths through {word} (line {line}): its value at the motion is the run's; assign it alike on every path, or after {word}"));
                }
                None => {}
            }
        }
        let names: std::collections::BTreeSet<String> =
            self.2.keys().chain(other.2.keys()).cloned().collect();
        for name in names {
            let (mine, theirs) = (self.2.get(&name), other.2.get(&name));
            if mine == theirs {
                continue;
            }
            let why = match (mine, theirs) {
                (Some(Err(w)), _) | (_, Some(Err(w))) => w.clone(),
                _ => format!("num {name} is set differently on the paths through {word} (line {line}): its value at the motion is the run's; set it alike on every path, or after {word}"),
            };
            self.2.insert(name, Err(why));
        }
    }
    fn agrees(&self, other: &Self) -> bool {
        self == other
    }
}

/// A procedure of the module called from another module: its name (lower case), what the call
/// binds its parameters to, where the call sits among the motions, the configuration monitoring
/// in force there.
pub(super) struct Entry {
    pub(super) name: String,
    pub(super) bindings: Bindings,
    pub(super) place: Place,
    pub(super) conf: Conf,
    /// Read alone: a routine with parameters of a module read whole (module `percall`).
    pub(super) alone: bool,
}

/// What a module read gives: its targets, the motions left, its routines, whether it switches
/// configuration monitoring (anywhere, and in the statements read).
pub(super) struct Module {
    pub(super) targets: Vec<JointTarget>,
    pub(super) left: Vec<Left>,
    pub(super) routines: Vec<(String, u64)>,
    pub(super) switches_conf: bool,
    pub(super) switches_own: bool,
}

/// A statement being read, where it sits among the motions, and its module's text and offset
/// in the whole text.
pub(super) struct Here<'s> {
    pub(super) statement: &'s Statement,
    pub(super) place: Place,
    pub(super) module: (&'s str, usize),
}
