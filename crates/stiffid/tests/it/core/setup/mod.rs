mod controller_robot;
mod numbered;
mod reference;
