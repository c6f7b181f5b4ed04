//! Stiffness files: JSON with the joint stiffness and, optionally, the covariance of the
//! compliance, as `stiffid identify --out` writes them (other keys are ignored):
//!
//! ```json
//! {"stiffness_nm_per_rad": [950000, 3000000, 900000, 250000, 200000, 150000],
//!  "compliance_covariance_rad2_per_nm2": [[...6 numbers...], ...6 rows...]}
//! ```

use crate::limits::{self, STIFFNESS_NM_PER_RAD};
use crate::{Error, Result};
use nalgebra::{Matrix6, Vector6};
use serde::{Deserialize, Serialize};

/// What a stiffness file holds, as its JSON keys (other keys of the file are ignored).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct StiffnessFile {
    /// The joint stiffness `k_i`, Nm/rad, joints 1..6; each within
    /// [`limits::STIFFNESS_NM_PER_RAD`].
    #[cfg_attr(
        feature = "schema",
        schemars(
            description = "The joint stiffness `k_i`, Nm/rad, joints 1..6.",
            inner(range(min = STIFFNESS_NM_PER_RAD.min, max = STIFFNESS_NM_PER_RAD.max))
        )
    )]
    #[serde(deserialize_with = "stiffness")]
    pub stiffness_nm_per_rad: [f64; 6],
    /// Optional: the covariance `Cov(h)` of the compliance `h_i = 1/k_i`, (rad/Nm)^2, row-major
    /// 6x6 (paper eq. 12); finite, symmetric, non-negative diagonal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[serde(deserialize_with = "crate::formats::exact::option_matrix")]
    pub compliance_covariance_rad2_per_nm2: Option<[[f64; 6]; 6]>,
}

/// Six stiffness values, exactly; a `null` (an infinitely stiff joint, as `identify
/// --nonnegative` writes a compliance at its bound) refused with what to do.
fn stiffness<'de, D: serde::Deserializer<'de>>(d: D) -> std::result::Result<[f64; 6], D::Error> {
    let k: [Option<f64>; 6] = crate::formats::exact::array(d)?;
    match k.iter().position(Option::is_none) {
        None => Ok(k.map(|v| v.unwrap_or_default())),
        Some(j) => Err(serde::de::Error::custom(format!(
            "stiffness_nm_per_rad[{}] is null: an infinitely stiff joint (a non-negative fit with its compliance at the bound 0), which no prediction can use; write a finite stiffness there (a large one for a stiff joint, within {} Nm/rad)",
            j + 1,
            STIFFNESS_NM_PER_RAD.max
        ))),
    }
}

/// What [`parse`] expects, for errors.
const EXPECTED: &str = "JSON with the key stiffness_nm_per_rad (six numbers, Nm/rad) and optionally compliance_covariance_rad2_per_nm2 (6x6)";

/// Parses and checks the text of a stiffness file.
///
/// # Errors
/// [`Error::Json`] (line, column) for text that is not JSON with these keys and shapes;
/// [`Error::InvalidField`] naming the key (and index) for a stiffness outside
/// [`limits::STIFFNESS_NM_PER_RAD`] or a covariance that is not finite, symmetric with a
/// non-negative diagonal ([`check_covariance`]).
///
/// # Examples
/// ```
/// let text = r#"{"setup": "any", "stiffness_nm_per_rad": [9.5e5, 3e6, 9e5, 2.5e5, 2e5, 1.5e5]}"#;
/// let file = stiffid::formats::stiffness::parse(text).unwrap();
/// assert_eq!(file.stiffness()[1], 3e6);
/// assert!(file.covariance().is_none());
/// ```
pub fn parse(text: &str) -> Result<StiffnessFile> {
    let file: StiffnessFile = serde_json::from_str(text).map_err(|e| {
        let message = e.to_string();
        let position = format!(" at line {} column {}", e.line(), e.column());
        Error::Json {
            line: e.line(),
            column: e.column(),
            message: message.strip_suffix(&position).unwrap_or(&message).into(),
            expected: EXPECTED,
        }
    })?;
    let k = &file.stiffness_nm_per_rad;
    limits::check("stiffness_nm_per_rad", k, &STIFFNESS_NM_PER_RAD)?;
    if let Some(c) = file.covariance() {
        check_covariance(&c)?;
    }
    Ok(file)
}

/// Checks a covariance `Cov(h)` of the compliance, (rad/Nm)^2 (the key
/// `compliance_covariance_rad2_per_nm2`; paper eq. 12): finite, symmetric to 1e-9 of the largest
/// diagonal entry, non-negative diagonal.
///
/// # Errors
/// [`Error::InvalidField`] naming `compliance_covariance_rad2_per_nm2`.
///
/// # Examples
/// ```
/// use nalgebra::Matrix6;
/// use stiffid::formats::stiffness::check_covariance;
/// assert!(check_covariance(&Matrix6::from_diagonal_element(1e-14)).is_ok());
/// assert!(check_covariance(&Matrix6::from_diagonal_element(-1e-14)).is_err());
/// ```
pub fn check_covariance(c: &Matrix6<f64>) -> Result<()> {
    let scale = c.diagonal().amax();
    let valid = c.iter().all(|v| v.is_finite())
        && c.diagonal().iter().all(|v| *v >= 0.0)
        && (c - c.transpose()).amax() <= 1e-9 * scale;
    match valid {
        true => Ok(()),
        false => Err(Error::InvalidField {
            field: "compliance_covariance_rad2_per_nm2".into(),
            message:
                "expected a symmetric 6x6 matrix of finite numbers with a non-negative diagonal"
                    .into(),
        }),
    }
}

impl StiffnessFile {
    /// The joint stiffness, Nm/rad.
    pub fn stiffness(&self) -> Vector6<f64> {
        Vector6::from(self.stiffness_nm_per_rad)
    }

    /// The covariance of the compliance, (rad/Nm)^2, if the file has it.
    pub fn covariance(&self) -> Option<Matrix6<f64>> {
        let rows = self.compliance_covariance_rad2_per_nm2?;
        Some(Matrix6::from_fn(|r, c| rows[r][c]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const K: &str = "[950000, 3000000, 900000, 250000, 200000, 150000]";

    fn covariance(c: &Matrix6<f64>) -> String {
        let rows: Vec<String> = c
            .row_iter()
            .map(|r| {
                format!(
                    "[{}]",
                    r.iter().map(f64::to_string).collect::<Vec<_>>().join(",")
                )
            })
            .collect();
        format!("[{}]", rows.join(","))
    }

    #[test]
    fn reads_stiffness_and_covariance() {
        let c = Matrix6::from_fn(|r, col| {
            if r == col {
                1e-12 * (r + 1) as f64
            } else {
                1e-14
            }
        });
        let text = format!(
            r#"{{"stiffness_nm_per_rad": {K}, "compliance_covariance_rad2_per_nm2": {}}}"#,
            covariance(&c)
        );
        let file = parse(&text).unwrap();
        assert_eq!(file.stiffness()[5], 150000.0);
        assert_eq!(file.covariance().unwrap(), c);
        let back = parse(&serde_json::to_string(&file).unwrap()).unwrap();
        assert_eq!(back, file);
    }

    #[test]
    fn errors_name_the_key_and_position() {
        let e = parse(r#"{"stiffness_nm_per_rad": [1, 2, 3, 4, 5, -6]}"#).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("stiffness_nm_per_rad[6]: -6 is outside"),
            "{e}"
        );
        let e = parse("{\n \"stiffness_nm_per_rad\": [1, 2]\n}").unwrap_err();
        // The length is known once the array is read: the position is at or just after it.
        assert!(matches!(e, Error::Json { line: 2..=3, .. }), "{e:?}");
        assert!(e.to_string().contains("expected JSON with the key"), "{e}");
        let mut c = Matrix6::identity() * 1e-12;
        c[(0, 1)] = 1e-13;
        let text = format!(
            r#"{{"stiffness_nm_per_rad": {K}, "compliance_covariance_rad2_per_nm2": {}}}"#,
            covariance(&c)
        );
        let e = parse(&text).unwrap_err().to_string();
        assert!(
            e.starts_with("compliance_covariance_rad2_per_nm2: expected a symmetric"),
            "{e}"
        );
    }
}
