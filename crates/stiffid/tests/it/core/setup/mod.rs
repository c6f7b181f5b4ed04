mod controller_robot;
mod load_steps;
mod numbered;
mod reference;
