//! The values a stiffness file may hold twice, checked to agree: the drives' compliance beside
//! their stiffness (`compliance_rad_per_nm`, as identify's document writes it), and the drives'
//! covariance beside every parameter's (`compliance_covariance_rad2_per_nm2` beside
//! `compliance_covariance_si`). One file, one stiffness: a value edited in one place and not in
//! the other is refused, naming both, rather than one of them silently read.

use super::{invalid, ParameterStiffness, StiffnessFile};
use crate::common::words::number;
use crate::model::ParameterKind;
use crate::Result;

/// The relative difference within which two copies of a value agree (the writer's rounding).
const AGREE: f64 = 1e-9;

/// Nothing when the drives' block of `si` (every parameter's covariance, SI) is `rows` (the
/// drives' covariance, (rad/Nm)^2), to [`AGREE`] of the block's largest entry.
///
/// # Errors
/// [`crate::Error::InvalidField`] (`compliance_covariance_rad2_per_nm2`) without `si` (beside
/// `parameters` the covariance read is `compliance_covariance_si`), or naming the first entry
/// that differs.
pub(super) fn check_covariances(
    parameters: &[ParameterStiffness],
    si: &Option<Vec<Vec<f64>>>,
    rows: &[[f64; 6]; 6],
) -> Result<()> {
    let field = "compliance_covariance_rad2_per_nm2";
    let Some(si) = si else {
        return Err(invalid(
            field.into(),
            "beside parameters, the covariance read is compliance_covariance_si (every \
             parameter's, SI, n x n), and this one, the drives' alone, would be ignored: give \
             compliance_covariance_si, or the drives alone (stiffness_nm_per_rad without \
             parameters)"
                .into(),
        ));
    };
    let drives: Vec<usize> = (parameters.iter().enumerate())
        .filter(|(_, p)| p.kind == ParameterKind::Drive)
        .map(|(i, _)| i)
        .collect();
    let largest = (drives.iter())
        .flat_map(|&a| drives.iter().map(move |&b| si[a][b].abs()))
        .fold(0.0, f64::max);
    for (r, &a) in drives.iter().enumerate().take(6) {
        for (c, &b) in drives.iter().enumerate().take(6) {
            if (rows[r][c] - si[a][b]).abs() > AGREE * largest {
                return Err(invalid(
                    format!("{field}[{}][{}]", r + 1, c + 1),
                    format!(
                        "{} where compliance_covariance_si gives {}: the file contradicts \
                         itself; keep one",
                        number(rows[r][c]),
                        number(si[a][b])
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The key of identify's document checked here.
#[derive(serde::Deserialize)]
struct Compliances {
    #[serde(default)]
    compliance_rad_per_nm: Option<Vec<Option<f64>>>,
}

/// Nothing when the file's `compliance_rad_per_nm`, if any, is `1 / k` of its drives' stiffness
/// (`stiffness_nm_per_rad`, or the drives of `parameters`), to [`AGREE`]; a `null` is not
/// compared.
///
/// # Errors
/// [`crate::Error::InvalidField`] (`compliance_rad_per_nm`) when it is not six numbers, or
/// naming the first that differs with the stiffness that gives another.
pub(super) fn check_compliance(text: &str, file: &StiffnessFile) -> Result<()> {
    let field = "compliance_rad_per_nm";
    let given = serde_json::from_str::<Compliances>(text)
        .ok()
        .map(|c| c.compliance_rad_per_nm);
    let h = match given {
        None => return Err(invalid(field.into(), "expected six numbers, rad/Nm".into())),
        Some(None) => return Ok(()),
        Some(Some(h)) if h.len() != 6 => {
            let got = h.len();
            return Err(invalid(
                field.into(),
                format!("expected six numbers, rad/Nm, got {got}"),
            ));
        }
        Some(Some(h)) => h,
    };
    let k: Vec<f64> = match (&file.stiffness_nm_per_rad, &file.parameters) {
        (Some(k), _) => k.to_vec(),
        (None, Some(p)) => (p.iter())
            .filter(|p| p.kind == ParameterKind::Drive)
            .map(|p| p.stiffness.unwrap_or(f64::NAN))
            .collect(),
        (None, None) => return Ok(()),
    };
    for (j, (h, k)) in h.iter().zip(&k).enumerate() {
        let Some(h) = h else { continue };
        if (h - 1.0 / k).abs() > AGREE * (1.0 / k).abs() {
            return Err(invalid(
                format!("{field}[{}]", j + 1),
                format!(
                    "{} where the stiffness {} Nm/rad gives {}: the file contradicts itself; \
                     keep one",
                    number(*h),
                    number(*k),
                    number(1.0 / k)
                ),
            ));
        }
    }
    Ok(())
}
