mod load_steps;
mod numbered;
mod prior;
mod reference;
