mod input;
mod output;
mod readings;
