mod configuration;
mod dynamics;
mod file;
mod urdf_write;
mod weight_file;
