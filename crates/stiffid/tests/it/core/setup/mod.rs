mod controller_axes;
mod controller_robot;
mod numbered;
mod reference;
