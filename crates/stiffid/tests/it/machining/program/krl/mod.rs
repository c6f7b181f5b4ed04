//! KUKA's KRL (`stiffid_machining::program::krl`).
mod arrays;
mod assign;
mod backup;
mod calls;
mod inline;
mod lists;
mod stored;
