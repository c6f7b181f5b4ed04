//! `calibrate --report` and `identify --report`: the reports render the jobs' documents (their
//! data equal the documents the commands print), fetch nothing, and the calibration's scene is a
//! glTF binary a reader parses.

use crate::calibrate_cli::{model, postures, readings, truth, SETUP};
use crate::common::{json, stiffid, temp_dir, write_file};
use serde_json::Value;
use std::path::Path;

const FANUC: &str = "fanuc-r2000ic-165f";
const FANUC_DATA: &str = "../../examples/data/fanuc-r2000ic-165f/measurements.csv";

/// `text` with each reading's tracker coordinates moved by a deterministic noise of about
/// `sd_mm` (uniform, the same standard deviation).
fn noisy(text: &str, sd_mm: f64, seed: u64) -> String {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * sd_mm * 12f64.sqrt()
    };
    let mut lines = text.lines();
    let mut out = format!("{}\n", lines.next().unwrap());
    for line in lines {
        let mut cells: Vec<String> = line.split(',').map(String::from).collect();
        let n = cells.len();
        for c in &mut cells[n - 3..] {
            *c = format!("{:?}", c.parse::<f64>().unwrap() + next());
        }
        out += &(cells.join(",") + "\n");
    }
    out
}

/// The page fetches nothing: no element loads a file, and the only absolute URLs are XML
/// namespaces (identifiers, never fetched).
fn fetches_nothing(html: &str) {
    for needle in [" src=", " href=", "url(", "@import"] {
        assert!(!html.contains(needle), "{needle}");
    }
    let mut at = 0;
    while let Some(i) = html[at..].find("://") {
        let start = at + i;
        let scheme = &html.as_bytes()[start.saturating_sub(5)..start];
        if scheme.ends_with(b"http") || scheme.ends_with(b"https") {
            assert!(
                html[start..].starts_with("://www.w3.org/"),
                "{}",
                &html[start..start + 40]
            );
        }
        at = start + 3;
    }
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let v: Vec<f64> = values.collect();
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}

#[test]
fn the_calibration_report_renders_the_document() {
    let d = temp_dir("report-calibrate");
    let model = model();
    let x = truth(&model);
    let tracker = crate::calibrate_cli::tracker();
    let fit = readings(&model, &x, &tracker, &postures(16, 1));
    let held = readings(&model, &x, &tracker, &postures(6, 2));
    let data = write_file(&d, "fit.csv", &noisy(&fit, 0.02, 3));
    let held = write_file(&d, "held.csv", &noisy(&held, 0.02, 4));
    let report = d.join("report");
    let args = [
        "calibrate",
        "--setup",
        SETUP,
        "--data",
        data.to_str().unwrap(),
        "--validate",
        held.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    // The report's document is the one printed.
    assert_eq!(read_json(&report.join("calibration.json")), doc);
    // Its errors are the document's own summaries, reading by reading (an independent sum).
    let errors = doc["errors"].as_array().unwrap();
    let set = |s: &'static str| errors.iter().filter(move |e| e["set"] == s);
    let norm = |e: &Value, k: &str| e[k].as_f64().unwrap();
    let fitted = rms(set("fitted").map(|e| norm(e, "after_norm_mm")));
    let nominal = rms(set("fitted").map(|e| norm(e, "before_norm_mm")));
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1e-6);
    assert!(
        close(fitted, doc["residual_rms_mm"].as_f64().unwrap()),
        "{fitted} {}",
        doc["residual_rms_mm"]
    );
    assert!(
        close(nominal, doc["nominal_rms_mm"].as_f64().unwrap()),
        "{nominal}"
    );
    let v = &doc["validation"];
    let held_after: Vec<f64> = set("validation")
        .map(|e| norm(e, "after_norm_mm"))
        .collect();
    let held_doc: Vec<f64> = (v["errors"].as_array().unwrap().iter())
        .map(|e| e["error_norm_mm"].as_f64().unwrap())
        .collect();
    assert_eq!(held_after, held_doc);
    assert!(close(
        rms(set("validation").map(|e| norm(e, "before_norm_mm"))),
        v["nominal_rms_mm"].as_f64().unwrap()
    ));
    assert!(
        fitted < 0.1 * nominal,
        "the calibration removes the errors: {fitted} of {nominal} mm"
    );
    // The page: the figures, the scene and the tables, fetching nothing.
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    fetches_nothing(&html);
    for needle in [
        "content=\"stiffid calibrate\"",
        "id=\"errors\"",
        "id=\"residuals\"",
        "id=\"parameters_mm\"",
        "scene-data",
        "Merged parameters",
    ] {
        assert!(html.contains(needle), "{needle}");
    }
    let first = &errors[0];
    // A tool's measuring point is named by its number, as in the readings.
    assert_eq!(first["point_name"], first["point"].to_string().as_str());
    let row = format!(
        "<td>fitted</td><td>{}</td><td>{}</td><td>{:.4}</td><td>{:.4}</td>",
        first["posture"].as_str().unwrap(),
        first["point_name"].as_str().unwrap(),
        norm(first, "before_norm_mm"),
        norm(first, "after_norm_mm")
    );
    assert!(html.contains(&row), "{row}");
    for m in doc["merged"].as_array().unwrap() {
        assert!(html.contains(m["name"].as_str().unwrap()));
    }
    // The scene as glTF binary: one node per fitted posture.
    let glb = std::fs::read(report.join("errors.glb")).unwrap();
    let g = gltf::Gltf::from_slice(&glb).unwrap();
    let names: Vec<_> = g
        .nodes()
        .filter_map(|n| n.name().map(String::from))
        .collect();
    assert!(
        names.contains(&"posture 16".to_string()) && !names.contains(&"posture 17".to_string())
    );
    assert!(
        report.join("figures/errors.svg").is_file() && !report.join("figures/errors.png").exists()
    );
    // Written again over its own report; never into a foreign directory.
    assert!(stiffid(&args).status.success());
    let foreign = d.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "mine").unwrap();
    let mut other = args.to_vec();
    other[8] = foreign.to_str().unwrap();
    let out = stiffid(&other);
    assert!(!out.status.success());
    assert_eq!(std::fs::read_dir(&foreign).unwrap().count(), 1);
}

#[test]
fn the_identification_report_renders_the_document() {
    let d = temp_dir("report-identify");
    let report = d.join("report");
    let args = [
        "identify",
        "--setup",
        FANUC,
        "--data",
        FANUC_DATA,
        "--cross-validate",
        "--report",
        report.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert_eq!(read_json(&report.join("identify.json")), doc);
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    fetches_nothing(&html);
    for needle in ["id=\"qq\"", "id=\"folds\"", "id=\"prediction\""] {
        assert!(html.contains(needle), "{needle}");
    }
    // The QQ plot draws one point per residual coordinate (plotters writes a circle each).
    let qq = std::fs::read_to_string(report.join("figures/qq.svg")).unwrap();
    let coordinates = 3 * doc["residuals"].as_array().unwrap().len();
    assert_eq!(qq.matches("<circle").count(), coordinates);
    let cv = &doc["cross_validation"];
    let sentence = format!("Cross-validation over {} folds", cv["folds"]);
    assert!(html.contains(&sentence), "{sentence}");
    // Each residual carries the measured displacement (the file's, the FANUC setup measuring in
    // the base frame) and the fitted one, their difference the residual.
    measured_is_the_file(&doc);
    for needle in ["id=\"measured\"", "id=\"parameters\""] {
        assert!(html.contains(needle), "{needle}");
    }
    let measured = std::fs::read_to_string(report.join("figures/measured.svg")).unwrap();
    assert_eq!(measured.matches("<circle").count(), coordinates);
    // The load tests in 3D: the page's scene and its glTF binary, one node per posture.
    assert!(html.contains("scene-data") && html.contains("The load tests in 3D"));
    let g = gltf::Gltf::from_slice(&std::fs::read(report.join("identify.glb")).unwrap()).unwrap();
    let postures = doc["postures"].as_u64().unwrap();
    let names: Vec<_> = g
        .nodes()
        .filter_map(|n| n.name().map(String::from))
        .collect();
    assert!(names.contains(&format!("posture {postures}")));
    assert!(!names.contains(&format!("posture {}", postures + 1)));

    let models = d.join("models");
    let args = [
        "identify",
        "--setup",
        FANUC,
        "--data",
        FANUC_DATA,
        "--compare-models",
        "--report",
        models.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert_eq!(read_json(&models.join("identify.json")), doc);
    let html = std::fs::read_to_string(models.join("report.html")).unwrap();
    fetches_nothing(&html);
    assert!(html.contains("id=\"models\""));
    assert!(!models.join("identify.glb").exists() && !html.contains("scene-data"));
    let rows = html.matches("<tr>").count();
    let expected = doc["models"].as_array().unwrap().len();
    assert!(rows > expected, "{rows} rows for {expected} models");
}

/// Every residual of the identify document `doc` of the FANUC data: its `measured_mm` is the
/// file's displacement on its line (to 1e-9 mm) and equals `predicted_mm + residual_mm`.
fn measured_is_the_file(doc: &Value) {
    let text = std::fs::read_to_string(FANUC_DATA).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let residuals = doc["residuals"].as_array().unwrap();
    assert!(!residuals.is_empty());
    let three = |v: &Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    for r in residuals {
        let line = r["line"].as_u64().unwrap() as usize;
        let cells: Vec<f64> = lines[line - 1]
            .split(',')
            .skip(11)
            .map(|c| c.parse().unwrap())
            .collect();
        let (m, p, e) = (
            three(&r["measured_mm"]),
            three(&r["predicted_mm"]),
            three(&r["residual_mm"]),
        );
        for a in 0..3 {
            assert!(
                (m[a] - cells[a]).abs() < 1e-9,
                "line {line}: {m:?} {cells:?}"
            );
            assert!((m[a] - p[a] - e[a]).abs() < 1e-12, "line {line}");
        }
    }
}

#[test]
fn the_identification_report_of_a_model_with_virtual_springs() {
    let d = temp_dir("report-identify-springs");
    let shown = stiffid(&["setups", "show", FANUC]);
    let spring =
        "\n[[model.spring]]\nname = \"bend\"\nkind = \"rotation\"\nlink = 3\naxis = [1, 0, 0]\n";
    let setup = write_file(
        &d,
        "springs.toml",
        &(String::from_utf8(shown.stdout).unwrap() + spring),
    );
    let report = d.join("report");
    let args = [
        "identify",
        "--setup",
        setup.to_str().unwrap(),
        "--data",
        FANUC_DATA,
        "--report",
        report.to_str().unwrap(),
        "--json",
    ];
    let doc = json(&stiffid(&args));
    assert_eq!(read_json(&report.join("identify.json")), doc);
    let names: Vec<&str> = (doc["parameters"].as_array().unwrap().iter())
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    assert_eq!(names.len(), 7);
    assert!(names.contains(&"bend"), "{names:?}");
    measured_is_the_file(&doc);
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    fetches_nothing(&html);
    for needle in [
        "id=\"measured\"",
        "id=\"parameters\"",
        "id=\"qq\"",
        "<td>bend</td>",
    ] {
        assert!(html.contains(needle), "{needle}");
    }
    // One interval per identified parameter (plotters draws each error bar as one path of its
    // stem and caps).
    let identified = (doc["parameters"].as_array().unwrap().iter())
        .filter(|p| p["ci95"].is_array())
        .count();
    assert!(identified >= 6, "{identified}");
    let measured = std::fs::read_to_string(report.join("figures/measured.svg")).unwrap();
    let coordinates = 3 * doc["residuals"].as_array().unwrap().len();
    assert_eq!(measured.matches("<circle").count(), coordinates);
}
