mod jacobi;
mod linalg;
mod spearman;
