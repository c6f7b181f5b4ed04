//! KUKA's KRL (`stiffid_machining::program::krl`).
mod inline;
mod stored;
