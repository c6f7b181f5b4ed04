//! File formats read by stiffid, as `&str -> Result<_, Error>` functions (no file I/O here): the
//! caller reads the file and adds its name to errors.
//!
//! - [`measurements`]: the measurement CSV of an identification or validation.
//! - [`path`]: the path (pose list) CSV of compensation.
//! - [`postures`]: the postures CSV of a group of postures.
//! - [`stiffness`]: the stiffness JSON (joint stiffness and the covariance of the compliance).

pub mod measurements;
pub mod path;
pub mod postures;
pub mod stiffness;
