//! The identify job's parts (`stiffid::app::identify`).

mod folds;
