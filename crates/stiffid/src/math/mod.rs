//! Numerical building blocks: the one-sided Jacobi SVD and condition numbers ([`linalg`]) and the
//! least-squares solvers by QR and SVD ([`lsq`]).

pub(crate) mod linalg;
pub mod lsq;
