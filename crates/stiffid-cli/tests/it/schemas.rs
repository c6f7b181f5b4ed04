//! The JSON Schemas in `docs/schemas/`: each is what `stiffid schema NAME` generates from the
//! types that write the document, and each validates the real output of its command (on the
//! built-in setups, the FANUC measurements, the milling path, ...) and rejects that output with
//! a key missing or an unknown key added.

use serde_json::Value;
use std::path::{Path, PathBuf};

use crate::common;

use common::{json, stiffid, temp_dir, write_file, GROUP};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn schema_path(name: &str) -> PathBuf {
    repo().join(format!("docs/schemas/{name}.schema.json"))
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap()
}

fn example(path: &str) -> String {
    repo().join("examples").join(path).display().to_string()
}

/// The names `stiffid schema` lists.
fn names() -> Vec<String> {
    let out = stiffid(&["schema"]);
    common::assert_success(&out);
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect()
}

#[test]
fn the_shipped_schemas_are_the_generated_ones() {
    let names = names();
    assert!(names.len() >= 10, "{names:?}");
    for name in &names {
        let out = stiffid(&["schema", name]);
        common::assert_success(&out);
        let shipped = std::fs::read(schema_path(name)).unwrap_or_default();
        assert!(
            shipped == out.stdout,
            "docs/schemas/{name}.schema.json is not what `stiffid schema {name}` generates; \
             regenerate it with: cargo run --release -p stiffid-cli -- schema {name} > docs/schemas/{name}.schema.json"
        );
    }
    let mut shipped: Vec<String> = std::fs::read_dir(repo().join("docs/schemas"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    shipped.sort();
    let mut expected: Vec<String> = names.iter().map(|n| format!("{n}.schema.json")).collect();
    expected.sort();
    assert_eq!(
        shipped, expected,
        "docs/schemas holds a schema stiffid does not generate"
    );
}

/// Asserts that `doc` is valid under the shipped schema `name`, and (a schema that can fail)
/// invalid without any one of its required keys and, for a `closed` schema, with an unknown key.
fn assert_valid(name: &str, doc: &Value, closed: bool) {
    let schema = read_json(&schema_path(name));
    let validator = jsonschema::validator_for(&schema).unwrap();
    let errors: Vec<String> = validator
        .iter_errors(doc)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect();
    assert!(errors.is_empty(), "{name}: {errors:#?}");
    let object = doc.as_object().unwrap();
    // The stiffness file requires one of two keys, which its schema cannot say: no `required`.
    for key in schema["required"].as_array().into_iter().flatten() {
        let mut missing = object.clone();
        missing.remove(key.as_str().unwrap());
        assert!(
            !validator.is_valid(&Value::Object(missing)),
            "{name}: valid without {key}"
        );
    }
    let mut extra = object.clone();
    extra.insert("an_unknown_key".into(), Value::Null);
    assert_eq!(
        validator.is_valid(&Value::Object(extra)),
        !closed,
        "{name}: an unknown key"
    );
}

#[test]
fn kinematics_and_predict_outputs_match_their_schemas() {
    // A wrist singularity: dexterity is null.
    let k = json(&stiffid(&[
        "kinematics",
        "--robot",
        "comau-smart5-nj165-3.0",
        "--q-deg",
        "0,0,-90,0,0,0",
        "--json",
    ]));
    assert!(k["dexterity"].is_null());
    assert_valid("kinematics", &k, true);
    // A stiffness file with the compliance covariance: every standard deviation is there.
    let p = json(&stiffid(&[
        "predict",
        "--setup",
        "fanuc-r2000ic-165f",
        "--q-deg",
        "0,10,-20,0,30,0",
        "--wrench",
        "100,-50,200,1,2,3",
        "--stiffness",
        &example("milling/stiffness.json"),
        "--json",
    ]));
    assert!(p["tcp_deflection_std_mm"].is_array());
    assert_valid("predict", &p, true);
}

#[test]
fn evaluate_and_select_outputs_match_their_schemas() {
    let dir = temp_dir("schemas-select");
    let group = write_file(&dir, "group.csv", GROUP);
    let group = group.to_str().unwrap();
    let cell = example("cell/zhang2021-tracker.toml");
    let e = json(&stiffid(&[
        "evaluate",
        "--setup",
        &cell,
        "--postures",
        group,
        "--json",
    ]));
    assert!(e["feasibility"][2]["violations"][0]["check"].is_string());
    assert_valid("evaluate", &e, true);

    let out = dir.join("local.csv");
    let local = json(&stiffid(&[
        "select",
        "--setup",
        &cell,
        "--start-random",
        "--max-evals",
        "20",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert!(local["unconstrained"].is_object());
    assert_valid("select", &local, true);
    // The criterion is one of the names `--criterion` takes.
    let validator = jsonschema::validator_for(&read_json(&schema_path("select"))).unwrap();
    let mut misspelt = local.clone();
    misspelt["criterion"] = Value::from("relative_a");
    assert!(!validator.is_valid(&misspelt));

    // A pool of the six postures, two more and one out of the bounds (skipped).
    let pool =
        format!("{GROUP}7,0,-30,-90,0,45,0\n8,20,-10,-120,60,-45,90\n9,0,-30,-90,0,45,359\n");
    let pool = write_file(&dir, "pool.csv", &pool);
    let out = dir.join("pool-out.csv");
    let chosen = json(&stiffid(&[
        "select",
        "--setup",
        "zhang2021-comau-nj165",
        "--pool",
        pool.to_str().unwrap(),
        "--target-pct",
        "50",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(chosen["pool"]["skipped"][0]["posture"], 9);
    assert!(chosen["target"]["steps"].is_array());
    assert_valid("select", &chosen, true);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn identify_validate_and_compensate_outputs_match_their_schemas() {
    let dir = temp_dir("schemas-identify");
    let data = common::fanuc_csv();
    let data = data.to_str().unwrap();
    let identify = |extra: &[&str]| json(&common::identify_fanuc(extra));
    let stiffness = dir.join("stiffness.json");
    let plain = identify(&["--folds", "4", "--out", stiffness.to_str().unwrap()]);
    assert!(plain["cross_validation"].is_object());
    assert_valid("identify", &plain, true);
    let robust = identify(&["--robust", "tukey"]);
    assert!(robust["robust"].is_object());
    assert_valid("identify", &robust, true);
    let bounded = identify(&["--nonnegative"]);
    assert!(bounded["active_bounds"].is_array());
    assert_valid("identify", &bounded, true);
    // What identify --out writes is a stiffness file; so is the milling example's.
    assert_valid("identify", &read_json(&stiffness), true);
    assert_valid("stiffness", &read_json(&stiffness), false);
    let example_file = read_json(Path::new(&example("milling/stiffness.json")));
    assert_valid("stiffness", &example_file, false);

    let stiffness = stiffness.to_str().unwrap();
    let v = json(&stiffid(&[
        "validate",
        "--setup",
        "fanuc-r2000ic-165f",
        "--stiffness",
        stiffness,
        "--data",
        data,
        "--json",
    ]));
    assert_valid("validate", &v, true);

    let out = dir.join("compensated.csv");
    let c = json(&stiffid(&[
        "compensate",
        "--setup",
        "fanuc-r2000ic-165f",
        "--stiffness",
        stiffness,
        "--path",
        &example("milling/path.csv"),
        "--out",
        out.to_str().unwrap(),
        "--free-tool-axis",
        "--json",
    ]));
    assert!(c["points"][0]["dx_std_mm"].is_number());
    assert_valid("compensate", &c, true);

    // --compare-models: the document, and the [model] fragment of --out read back by a setup.
    let fragment = dir.join("model.toml");
    let m = identify(&["--compare-models", "--out", fragment.to_str().unwrap()]);
    assert_valid("compare-models", &m, true);
    let models = m["models"].as_array().unwrap();
    let drives = models[0]["held_out_explained"].as_f64().unwrap();
    assert!((drives - 0.765).abs() < 5e-4, "{drives}");
    let rec = models.iter().find(|r| r["recommended"] == true).unwrap();
    assert!(rec["held_out_explained"].as_f64().unwrap() >= 0.81 && rec["physical"] == true);
    let setup = dir.join("with-model.toml");
    let text = stiffid::setup::builtin_text("fanuc-r2000ic-165f")
        .unwrap()
        .to_string()
        + &std::fs::read_to_string(&fragment).unwrap();
    std::fs::write(&setup, text).unwrap();
    let fit = json(&stiffid(&[
        "identify",
        "--setup",
        setup.to_str().unwrap(),
        "--data",
        data,
        "--json",
    ]));
    let names: Vec<&str> = fit["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names.len(), rec["parameters"].as_u64().unwrap() as usize);
    assert_eq!(&names[..6], ["k1", "k2", "k3", "k4", "k5", "k6"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn simulate_and_reproduce_outputs_match_their_schemas() {
    let dir = temp_dir("schemas-study");
    let group = write_file(&dir, "group.csv", GROUP);
    let s = json(&stiffid(&[
        "simulate",
        "--setup",
        "zhang2021-comau-nj165",
        "--postures",
        group.to_str().unwrap(),
        "--runs",
        "5",
        "--json",
    ]));
    assert_valid("simulate", &s, true);

    let report = dir.join("report");
    let out = stiffid(&[
        "reproduce",
        "--out",
        report.to_str().unwrap(),
        "--runs",
        "5",
        "--starts",
        "2",
        "--trials",
        "2",
    ]);
    common::assert_success(&out);
    assert_valid("reproduce", &read_json(&report.join("summary.json")), true);
    let _ = std::fs::remove_dir_all(&dir);
}
