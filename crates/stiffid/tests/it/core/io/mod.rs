mod input;
mod measurements;
mod output;
mod readings;
