mod external;
mod input;
mod measurements;
mod output;
mod postures;
mod readings;
mod stiffness;
mod text;
