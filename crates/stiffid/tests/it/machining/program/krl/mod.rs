//! KUKA's KRL (`stiffid_machining::program::krl`).
mod corpus;
mod inline;
mod stored;
