//! KUKA's KRL (`stiffid_machining::program::krl`).

mod cartesian;
mod corpus;
mod inline;
mod stored;
