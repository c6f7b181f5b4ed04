mod file;
mod prediction;
