//! ABB's RAPID (`stiffid_machining::program::rapid`).

mod backup;
mod computed;
mod corpus;
mod flow;
mod module;
mod offsets;
pub(crate) mod robots;
pub(crate) mod stored;
mod task;
pub(crate) mod track;
