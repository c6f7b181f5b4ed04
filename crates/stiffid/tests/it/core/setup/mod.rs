mod controller_robot;
mod reference;
