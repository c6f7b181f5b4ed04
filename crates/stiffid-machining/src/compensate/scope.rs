//! What one configuration of the free configuration holds: the whole program, or each run
//! between rapid moves (`--free configuration=run`).

/// What one configuration of the free configuration holds (`--free configuration=run`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scope {
    /// The whole path or program: no change of configuration anywhere.
    #[default]
    Program,
    /// Each run ([`super::starts`]): the arm may change configuration in the joint move that starts
    /// a run.
    Run,
}

impl stiffid_core::common::choice::Choice for Scope {
    const FIELD: &'static str = "configuration_per";
    const ALL: &'static [Self] = &[Scope::Program, Scope::Run];
    fn name(self) -> &'static str {
        match self {
            Scope::Program => "program",
            Scope::Run => "run",
        }
    }
    fn help(self) -> &'static str {
        match self {
            Scope::Program => "One configuration holds the whole program",
            Scope::Run => "Each run between rapid moves takes its own configuration",
        }
    }
}

stiffid_core::common::choice::by_name!(Scope);
