//! The figures of the paper's study (`stiffid reproduce`, Python's `stiffid.reproduce(...,
//! figures=True)`), from the study the job returns: the deviation rate against the noise
//! ([`deviation`], the paper's Fig. 8), Table 4 as a figure ([`table`]), each design criterion
//! against the measured deviation ([`criteria`]) and each group's postures
//! ([`crate::postures::figure`]).

pub mod criteria;
pub mod deviation;
pub mod table;

use crate::Drawing;
use stiffid_design::study::{criterion_values, Study};
use stiffid_design::Evaluation;

/// The design criteria the study's report compares, keyed as in `stiffid evaluate`, with what
/// they measure.
pub const CRITERIA: [(&str, &str); 7] = [
    (
        "classical",
        "max k(J_N) over the postures (the paper's classical index)",
    ),
    (
        "zhang2021",
        "classical x cond(Psi) (the paper's novel index)",
    ),
    ("scaled_cond", "cond(Psi diag(h) / sigma), scale-free"),
    (
        "d_optimal",
        "geometric mean relative std of the compliances at level 1",
    ),
    (
        "relative_a",
        "RMS relative std of the compliances at level 1",
    ),
    (
        "test_pose_mm",
        "RMS error of the deflection predicted at the test postures, mm",
    ),
    ("cond_psi", "cond(Psi) in SI units"),
];

/// The values of [`CRITERIA`] of one group, in that order (the library's [`criterion_values`],
/// `test_pose_mm` in mm).
pub fn criteria_values(e: &Evaluation) -> [(&'static str, f64); 7] {
    let mut v = criterion_values(e);
    v[5] *= 1e3;
    std::array::from_fn(|i| (CRITERIA[i].0, v[i]))
}

/// Every figure of the study, in report order: `deviation_vs_noise`, `table4_level2`,
/// `criteria_vs_deviation`, then `postures_<group>` per group.
pub fn figures(study: &Study) -> Vec<Drawing<'_>> {
    let mut all = vec![
        deviation::figure(study),
        table::figure(study),
        criteria::figure(study),
    ];
    all.extend((0..study.groups.len()).map(|g| crate::postures::figure(study, g)));
    all
}
