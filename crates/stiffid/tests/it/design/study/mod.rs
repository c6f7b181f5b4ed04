//! The paper's study (`stiffid_design::study`).

mod observability;
