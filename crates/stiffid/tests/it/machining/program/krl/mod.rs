//! KUKA's KRL (`stiffid_machining::program::krl`).

mod cartesian;
