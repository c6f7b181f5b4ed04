//! KUKA's KRL (`stiffid_machining::program::krl`).
mod backup;
mod inline;
mod lists;
mod stored;
