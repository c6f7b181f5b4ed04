mod load_steps;
mod prior;
mod reference;
