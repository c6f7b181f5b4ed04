//! The choice of a group of postures as `select` makes it: the group chosen by a search or from
//! a pool ([`search`]), the pool's postures screened by the cell's checks ([`pool`]), where a
//! robot on external axes stands for it ([`station`]), a calibration campaign over a track's
//! stations ([`campaign`]) and the positioner's angles of a calibration group's table readings
//! ([`table`]). Inputs and results in SI; errors [`stiffid_core::Error`].

pub mod campaign;
pub mod pool;
pub mod search;
pub mod station;
pub mod table;

#[cfg(test)]
mod pool_tests;

#[cfg(test)]
mod station_tests;

#[cfg(test)]
mod table_tests;
