//! What the metrology jobs share: the tracker readings they read and check.

pub mod readings;
