//! The design crate's tests (`stiffid_design`), through its public paths: the selection.
mod selection;
