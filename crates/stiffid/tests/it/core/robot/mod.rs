mod collision;
mod configuration;
mod dynamics;
mod error_map;
mod external;
mod file;
mod urdf_write;
mod weight_file;
