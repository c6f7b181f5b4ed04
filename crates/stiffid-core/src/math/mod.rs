//! Numerical building blocks: the one-sided Jacobi SVD and condition numbers ([`jacobi`]), the
//! six-column QR kernels ([`linalg`]) and the least-squares solvers by QR and SVD ([`lsq`]).

pub mod jacobi;
pub mod linalg;
pub mod lsq;
