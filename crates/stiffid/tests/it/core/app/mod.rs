mod document;
mod setups_new;
