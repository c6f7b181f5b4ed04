//! Cutting-coefficient presets for milling, each with its published source.
//!
//! Only values read in their source are shipped. Both rows are as tabulated in Table 5 of
//! the review "Milling Force Model for Aviation Aluminum Alloy: Academic Insight and
//! Perspective Analysis", Chinese Journal of Mechanical Engineering 34, 2021,
//! doi:10.1186/s10033-021-00536-9 (cemented carbide end mills, dry), which cites the original
//! identifications (its references 189 and 190). Coefficients depend on the tool's geometry and
//! coating: identify your own (slot-milling tests at several feeds, Altintas ch. 2.4) for
//! anything better than an estimate.

use super::milling::Coefficients;

/// A material preset: its name, the coefficients and where they come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Preset {
    /// The name a process file uses (`preset = "al7075-t6"`).
    pub name: &'static str,
    /// The material and the tool.
    pub material: &'static str,
    /// The coefficients, SI.
    pub coefficients: Coefficients,
    /// The published source of the numbers.
    pub source: &'static str,
}

const REVIEW: &str = "Table 5 of 'Milling Force Model for Aviation Aluminum Alloy: Academic Insight and Perspective Analysis', Chinese Journal of Mechanical Engineering 34 (2021), doi:10.1186/s10033-021-00536-9";

/// Coefficients from N/mm^2 and N/mm: `[k_tc, k_rc, k_ac]`, `[k_te, k_re, k_ae]`.
const fn si(cutting: [f64; 3], edge: [f64; 3]) -> Coefficients {
    Coefficients {
        k_tc: cutting[0] * 1e6,
        k_rc: cutting[1] * 1e6,
        k_ac: cutting[2] * 1e6,
        k_te: edge[0] * 1e3,
        k_re: edge[1] * 1e3,
        k_ae: edge[2] * 1e3,
    }
}

/// Every preset.
pub(crate) const PRESETS: [Preset; 2] = [
    Preset {
        name: "al7075-t6",
        material: "aluminium 7075-T6, cemented carbide end mill, dry",
        coefficients: si([767.01, 168.8, 222.0], [27.7, 26.6, 0.7]),
        source: REVIEW,
    },
    Preset {
        name: "al6082-t6",
        material: "aluminium 6082-T6, cemented carbide end mill, dry",
        coefficients: si([631.0, 99.0, 273.0], [13.0, 10.0, 2.8]),
        source: REVIEW,
    },
];

/// The preset named `name`.
pub(crate) fn find(name: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.name == name)
}
