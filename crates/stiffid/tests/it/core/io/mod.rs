mod external;
mod input;
mod output;
mod postures;
mod readings;
mod stiffness;
