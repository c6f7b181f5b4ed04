mod body;
mod modes;
