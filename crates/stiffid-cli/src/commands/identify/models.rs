//! `stiffid identify` over a model with virtual springs, and `--compare-models`: the library's
//! fits ([`stiffid::identify::model`], [`stiffid::identify::compare`]) rendered as text or JSON.

use super::Args;
use crate::load;
use crate::output::{self, json, OutFile};
use anyhow::{bail, Context, Result};
use serde::Serialize;
use stiffid::identify::compare::{
    candidates_by_name, compare, default_candidates, parameter_docs, Comparison, Row,
};
use stiffid::identify::model::{fit, fit_nonnegative, Fit};
use stiffid::observation::Observations;
use stiffid::Setup;

/// `--compare-models`: the table, the recommendation, `--out` the recommended `[model]`.
pub fn compare_models(args: &Args, setup: &Setup) -> Result<()> {
    if args.robust.is_some() || args.nonnegative || args.cross_validate || args.folds.is_some() {
        bail!("--compare-models compares least-squares fits held out posture by posture: leave out --robust, --nonnegative, --cross-validate and --folds");
    }
    let out = args
        .out
        .as_deref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let file = load::measurements(&args.data, setup)?;
    let candidates = match &args.candidates {
        Some(names) => candidates_by_name(setup, names).context("--candidates")?,
        None => default_candidates(setup),
    };
    let name = args.data.display().to_string();
    let c = compare(setup, &file.measurements, &candidates, true)
        .map_err(|e| file.explain(e))
        .with_context(|| name.clone())?;
    if let Some(out) = &out {
        let text = format!(
            "# The model `stiffid identify --compare-models` recommends for {name}: paste into the setup.\n{}",
            stiffid::model::fragment(&c.recommended_springs)
        );
        out.write(text.as_bytes())?;
    }
    let doc = c.document(&args.common.setup, &name, setup.noise().variance);
    match args.common.json {
        true => output::print(&json(&doc)?),
        false => output::print(&text(&c)),
    }
}

fn pct(v: Option<f64>) -> String {
    v.map_or("n/a".into(), |v| format!("{:.1}%", 100.0 * v))
}

fn row_line(r: &Row, mark: &str) -> String {
    let what = r.added.clone().unwrap_or_else(|| "(setup's model)".into());
    format!(
        "{mark:1} {what:<16} {:>3} {:>9} {:>9} {:>10} {:>9.1} {:>9.1} {:>7} {:>8}\n",
        r.parameters,
        pct(Some(r.in_sample_explained)),
        pct(r.held_out_explained),
        r.held_out_rms_delta_b
            .map_or("n/a".into(), |v| format!("{:.4}", v * 1e3)),
        r.aic,
        r.bic,
        r.noise_ratio.map_or("n/a".into(), |v| format!("{v:.2}")),
        match (r.physical, r.identified) {
            (_, false) => "unident.",
            (true, true) => "yes",
            (false, true) => "no",
        }
    )
}

const HEADER: &str =
    "  added            par in-sample  held out  dB RMS mm       AIC       BIC   noise  all k>0\n";

/// The text report of a comparison.
fn text(c: &Comparison) -> String {
    let mut s =
        String::from("Model comparison: forward selection on the leave-one-posture-out error\n\n");
    s += "Selected path (* recommended):\n";
    s += HEADER;
    for (i, r) in c.models.iter().enumerate() {
        s += &row_line(r, if i == c.recommended { "*" } else { "" });
    }
    for (k, step) in c.steps.iter().enumerate() {
        s += &format!(
            "\nStep {}: every candidate added to the model of step {k}\n",
            k + 1
        );
        s += HEADER;
        for (i, r) in step.candidates.iter().enumerate() {
            s += &row_line(r, if step.chosen == Some(i) { ">" } else { "" });
        }
    }
    if let Some(n) = &c.nested {
        let chosen: Vec<String> = n
            .chosen
            .iter()
            .filter(|(_, k)| *k > 0)
            .map(|(name, k)| format!("{name} {k}/{}", n.parameters.len()))
            .collect();
        s += &format!(
            "\nNested estimate (the whole selection repeated without each posture): held out {} explained, RMS delta_b {:.4} mm; chosen: {}\n",
            pct(Some(n.held_out_explained)),
            n.rms_delta_b * 1e3,
            if chosen.is_empty() { "nothing".into() } else { chosen.join(", ") }
        );
    }
    s += "\nRecommended model fitted to every posture:\n";
    s += &fit_table(&c.recommended_fit);
    s += &format!("\n{}\n", c.conclusion());
    s
}

/// The parameters of a fit with 95% intervals, and what the data cannot identify.
pub fn fit_table(f: &Fit) -> String {
    let mut s = format!(
        "  {:<12} {:>14} {:>31}  unit\n",
        "parameter", "stiffness", "95% interval"
    );
    for p in parameter_docs(f) {
        let v = p.stiffness.map_or("n/a".into(), |v| format!("{v:.0}"));
        let ci = match (p.identified, p.ci95) {
            (false, _) => "not identifiable".to_string(),
            (true, None) => "n/a".into(),
            (true, Some([lo, hi])) => format!(
                "[{}, {}]",
                lo.map_or("inf".into(), |v| format!("{v:.0}")),
                hi.map_or("inf".into(), |v| format!("{v:.0}"))
            ),
        };
        s += &format!("  {:<12} {v:>14} {ci:>31}  {}\n", p.name, p.unit);
    }
    for c in &f.identifiability.unidentifiable {
        s += &format!(
            "  the data cannot separate: {}\n",
            c.describe(&f.parameters)
        );
    }
    s
}

/// The fit of a setup whose model has virtual springs.
#[derive(Serialize)]
struct ModelFitJson {
    setup: String,
    data: String,
    method: &'static str,
    rows: usize,
    postures: usize,
    #[serde(flatten)]
    fit: stiffid::identify::compare::document::FitDoc,
    chi2_p_value: Option<f64>,
}

/// `stiffid identify` with a setup whose model has virtual springs: least squares or
/// `--nonnegative`, every parameter with its unit and interval, what is not identifiable;
/// `--out` the stiffness file of every parameter (what `--stiffness` reads).
pub fn identify_model(args: &Args, setup: &Setup) -> Result<()> {
    if args.robust.is_some() || args.cross_validate || args.folds.is_some() {
        bail!("a model with virtual springs is identified by least squares or --nonnegative; --robust, --cross-validate and --folds take the six drives alone (use --compare-models for the held-out error)");
    }
    let file = load::measurements(&args.data, setup)?;
    let out = args
        .out
        .as_deref()
        .map(|p| OutFile::prepare(p, "--out"))
        .transpose()?;
    let name = args.data.display().to_string();
    let obs = Observations::from_measurements(setup, &file.measurements)
        .map_err(|e| file.explain(e))
        .with_context(|| name.clone())?;
    let parameters = setup.model().parameters();
    let f = match args.nonnegative {
        true => fit_nonnegative(&obs, &parameters),
        false => fit(&obs, &parameters),
    }
    .with_context(|| name.clone())?;
    let variance = setup.noise().variance;
    if !f.identifiability.unidentifiable.is_empty() {
        output::warn(&format!(
            "the data cannot identify every parameter ({} combinations): no intervals for those",
            f.identifiability.unidentifiable.len()
        ));
    }
    if !f.physical() {
        output::warn("not every compliance is positive (not physical): try --nonnegative or fewer springs (--compare-models)");
    }
    if args.common.json || out.is_some() {
        let text = json(&ModelFitJson {
            setup: args.common.setup.clone(),
            data: name,
            method: if args.nonnegative {
                "nonnegative-least-squares"
            } else {
                "least-squares"
            },
            rows: f.rows,
            postures: f.postures,
            fit: stiffid::identify::compare::document::fit_doc(&f, variance),
            chi2_p_value: f.adequacy_p_value(variance),
        })?;
        if let Some(out) = &out {
            out.write(text.as_bytes())?;
        }
        if args.common.json {
            return output::print(&text);
        }
    }
    let mut s = format!(
        "Stiffness of a {}-parameter model from {} postures ({} rows)\n",
        f.parameters.len(),
        f.postures,
        f.rows
    );
    s += &fit_table(&f);
    if let Some(r) = f.noise_ratio(variance) {
        s += &format!("residual std / tracker noise: {r:.2}\n");
    }
    output::print(&s)
}
