//! The calibration from one tracker campaign (`stiffid_metrology::calibration`): `tests` holds
//! the shared campaigns (postures, points, tracker, readings) and the geometry and gravity cases;
//! one module per further part of the error model.

use stiffid_metrology::calibration::*;

mod arm_tests;
mod backlash_tests;
mod external_tests;
mod fixed_tables_tests;
mod heavy_tests;
mod intervals_tests;
mod loaded_tests;
mod maps_kernel_tests;
mod maps_tests;
mod masses_tests;
mod tests;
mod thin_tests;
