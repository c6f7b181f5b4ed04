//! `compensate` with the stiffness file of `identify --compare-models --bootstrap N
//! --stiffness-out`: the file carries the recommended model fitted to every posture, and the
//! compensate document sets it beside the file's own model (the six drives) at every point.

use crate::common;

use common::{example, identify_fanuc, json, stiffid, temp_dir, write_file};

/// On the real FANUC data, seven holes at joint 6 turned in 30 deg steps, 600 N along the tool:
/// `model_ranking` lists every point with the drives' deflection (the row's `d_norm_mm`) and
/// the recommended model's, its rho is Spearman's of the two, `agree` says whether it reaches
/// 0.5 and a `model-form` warning comes exactly when it does not; a file without the recommended
/// model gives no ranking.
#[test]
fn compensate_sets_the_recommended_model_beside_the_drives() {
    let dir = temp_dir("model-ranking");
    let k = dir.join("k.json");
    let out = identify_fanuc(&[
        "--compare-models",
        "--bootstrap",
        "5",
        "--stiffness-out",
        k.to_str().unwrap(),
    ]);
    common::assert_success(&out);
    let mut file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&k).unwrap()).unwrap();
    let recommended = &file["model_form"]["recommended"];
    assert_eq!(recommended["compliance_si"].as_array().unwrap().len(), 1);
    assert!(!recommended["springs"].as_array().unwrap().is_empty());
    let mut path = String::from("q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,fx_n,fy_n,fz_n,frame\n");
    for k in 0..7 {
        path += &format!("-84,-54,-33,52,-119,{},0,0,600,tool\n", -5 + 30 * k);
    }
    let hole = write_file(&dir, "hole.csv", &path);
    let compensate = |stiffness: &std::path::Path| {
        let setup = example("milling/fanuc-milling.toml");
        let args = ["compensate", "--setup", &setup, "--stiffness"];
        let (k, p) = (stiffness.to_str().unwrap(), hole.to_str().unwrap());
        let csv = stiffness.with_extension("csv");
        let csv = csv.to_str().unwrap();
        let out = stiffid(&[&args[..], &[k, "--path", p, "--out", csv, "--json"]].concat());
        common::assert_success(&out);
        json(&out)
    };
    let doc = compensate(&k);
    let ranking = &doc["model_ranking"];
    assert_eq!(ranking["points"], 7);
    assert_eq!(ranking["threshold_rho"], 0.5);
    let listed = ranking["largest_rank_differences"].as_array().unwrap();
    assert_eq!(listed.len(), 7);
    let rows = doc["points"].as_array().unwrap();
    let value = |p: &serde_json::Value, key: &str| p[key].as_f64().unwrap();
    for p in listed {
        let row = &rows[p["line"].as_u64().unwrap() as usize - 2];
        let d = value(row, "d_norm_mm");
        assert!(
            (value(p, "deflection_mm") - d).abs() <= 1e-9 * d,
            "{p} against {row}"
        );
    }
    // rho from the listed values: Spearman's rank correlation (no ties), 1 - 6 sum d^2 / (n^3 - n).
    let d2: f64 = listed
        .iter()
        .map(|p| (value(p, "rank") - value(p, "recommended_rank")).powi(2))
        .sum();
    let rho = 1.0 - 6.0 * d2 / (7.0 * 48.0);
    assert!(
        (ranking["rho"].as_f64().unwrap() - rho).abs() < 1e-12,
        "{ranking}"
    );
    assert_eq!(ranking["agree"], rho >= 0.5);
    let warned = (doc["warnings"].as_array().unwrap().iter()).any(|w| w["kind"] == "model-form");
    assert_eq!(warned, rho < 0.5);
    // Without the recommended model the file is read as before, and nothing is compared.
    file["model_form"]
        .as_object_mut()
        .unwrap()
        .remove("recommended");
    let plain = write_file(&dir, "plain.json", &file.to_string());
    assert!(compensate(&plain)["model_ranking"].is_null());
}
