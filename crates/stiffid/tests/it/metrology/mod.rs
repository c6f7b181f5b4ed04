//! The metrology crate's tests (`stiffid_metrology`), through its public paths: the robot's
//! calibration from tracker readings and the tracker's registration.

mod calibration;
