//! The `model_form` of the stiffness file `identify --compare-models --bootstrap N
//! --stiffness-out` writes: the models the data support and their resampled parameter sets
//! ([`stiffid_core::io::stiffness::ModelFormSection`]) for compensation's error budget, and the
//! recommended model fitted to every posture, which compensation sets beside the file's own.

use stiffid_core::io::stiffness::{FormModelSection, FormSpring, ModelFormSection};
use stiffid_core::model::Spring;
use stiffid_identify::compare::{Bootstrap, Comparison};

/// The section of the bootstrap `b`, `springs` the virtual springs of the setup's model then
/// the candidates (parameter `j >= 6` is `springs[j - 6]`): the resamples' supported models,
/// each model's parameters in ascending order, its sets in resample order; and `c`'s
/// recommended model fitted to every posture.
pub(super) fn section(b: &Bootstrap, c: &Comparison, springs: &[Spring]) -> ModelFormSection {
    let mut models: Vec<(Vec<usize>, Vec<Vec<f64>>)> = Vec::new();
    for (indices, h) in b.supported.iter().flatten() {
        let mut order: Vec<usize> = (0..indices.len()).collect();
        order.sort_by_key(|&k| indices[k]);
        let key: Vec<usize> = order.iter().map(|&k| indices[k]).collect();
        let set = order.iter().map(|&k| h[k]).collect();
        match models.iter_mut().find(|m| m.0 == key) {
            Some(m) => m.1.push(set),
            None => models.push((key, vec![set])),
        }
    }
    let recommended = (c.recommended_springs.iter())
        .filter_map(|r| springs.iter().position(|s| s.name == r.name).map(|k| k + 6));
    let mut used: Vec<usize> = (models.iter())
        .flat_map(|m| m.0[6..].to_vec())
        .chain(recommended)
        .collect();
    used.sort_unstable();
    used.dedup();
    ModelFormSection {
        resamples: b.resampling.resamples as u64,
        seed: b.resampling.seed,
        recommended: Some(FormModelSection {
            springs: c
                .recommended_springs
                .iter()
                .map(|s| s.name.clone())
                .collect(),
            compliance_si: vec![c.recommended_fit.compliance.iter().copied().collect()],
        }),
        springs: used
            .iter()
            .map(|&j| FormSpring::new(&springs[j - 6]))
            .collect(),
        models: (models.into_iter())
            .map(|(key, sets)| FormModelSection {
                springs: key[6..]
                    .iter()
                    .map(|&j| springs[j - 6].name.clone())
                    .collect(),
                compliance_si: sets,
            })
            .collect(),
    }
}
