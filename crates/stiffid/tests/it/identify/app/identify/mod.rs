//! The identify job's parts (`stiffid_identify::app::identify`).

mod folds;
