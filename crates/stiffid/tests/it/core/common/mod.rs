mod limits;
mod stop;
mod words;
