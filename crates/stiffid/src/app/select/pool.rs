//! The request's pool of candidate postures screened by the cell's checks
//! ([`stiffid_design::selection::pool`]), and what was chosen from it.

use super::{PoolInput, PoolReport, Request};
use stiffid_core::Result;
pub(super) use stiffid_design::selection::pool::{in_pool, Screened as Candidates};
use stiffid_design::PoolMethod;

/// The pool `input` of the request: the postures that fail a check of the cell with the
/// request's margin skipped, and those that are not distinct with [`Request::distinct`].
pub(super) fn screened<'a>(request: &Request<'a>, input: &'a PoolInput) -> Result<Candidates<'a>> {
    Candidates::new(
        request.setup,
        &input.name,
        &input.postures,
        request.options.margin,
        request.distinct.as_ref(),
    )
}

/// What the pool held and what was chosen from it.
pub(super) fn report(pool: Candidates, chosen: Option<(Vec<usize>, PoolMethod)>) -> PoolReport {
    let (chosen, method) = chosen.expect("a pool choice");
    PoolReport {
        name: pool.name.into(),
        total: pool.total,
        usable: pool.usable(),
        skipped: pool.skipped,
        method,
        chosen,
        not_distinct: pool.not_distinct,
    }
}
