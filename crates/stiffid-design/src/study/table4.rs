//! The paper's Table 4, and whether a study can be set beside it.

use super::Study;

/// The paper's Table 4: deviation rates (%) of one simulation run at noise level 2 (variance
/// multiple 1), [joint 1-6][Group 1-3] (Zhang et al. 2021, Section IV-A).
const TABLE4: [[f64; 3]; 6] = [
    [0.726, 0.339, 0.268],
    [1.413, 9.845, 0.820],
    [0.251, 0.488, 0.002],
    [7.304, 2.259, 2.075],
    [2.712, 2.236, 0.045],
    [3.242, 2.364, 0.469],
];

/// The built-in setup of the paper's study.
const PAPER_SETUP: &str = "zhang2021-comau-nj165";

/// The paper's Table 4 if the study compares with it: the study ran on the paper's setup
/// (`zhang2021-comau-nj165`) and validates at the paper's level 2; `None` otherwise. Only orders
/// of magnitude compare: the paper's table is one run, the study's numbers are means over runs.
pub fn paper_table4(study: &Study) -> Option<&'static [[f64; 3]; 6]> {
    (study.setup.name() == PAPER_SETUP && study.validation_level == 1).then_some(&TABLE4)
}
