//! ABB's RAPID (`stiffid_machining::program::rapid`).

mod flow;
