//! Numerical building blocks: the one-sided Jacobi SVD and condition numbers ([`jacobi`]), the
//! Householder reflections and QR of any number of columns ([`householder`]), the six-column
//! kernels ([`linalg`]), the least-squares solvers by QR and SVD ([`lsq`]) and
//! Spearman's rank correlation ([`spearman`]).

pub mod householder;
pub mod jacobi;
pub mod linalg;
pub mod lsq;
mod spearman;

pub use spearman::{ranks, spearman};

#[cfg(test)]
mod householder_tests;
#[cfg(test)]
mod jacobi_tests;
#[cfg(test)]
mod linalg_tests;
