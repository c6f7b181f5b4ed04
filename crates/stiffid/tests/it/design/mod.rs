//! The design crate's tests (`stiffid_design`), through its public paths: the criteria, the pool, the searches and the study.

mod evaluator;
mod exchange;
mod observability;
mod pool;
mod registration;
mod search;
mod selection;
mod study;
mod termination;
