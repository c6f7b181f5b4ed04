//! File formats, parsed from text (`&str -> Result<_, Error>`): no file I/O here.

pub mod path;
