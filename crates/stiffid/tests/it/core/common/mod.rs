mod limits;
mod stop;
