//! `stiffid identify` over a model with virtual springs, and `--compare-models`: the library's
//! fits ([`stiffid::internal::identify::svd`], [`stiffid::internal::identify::compare`]) rendered as text.

use super::text;
use stiffid::app::document::mm;
use stiffid::app::identify::document::springs::{CrossValidationDoc, Document};
use stiffid::app::identify::springs::Report;
use stiffid::internal::common::words::count;
use stiffid::internal::identify::adequacy::Verdict;
use stiffid::internal::identify::compare::document::{
    BootstrapDoc, Document as CompareDocument, ModelDoc,
};
use stiffid::internal::identify::compare::{parameter_docs, Comparison};
use stiffid::internal::identify::svd::Fit;
use stiffid::Setup;

/// The bootstrap's table from its document.
fn bootstrap_text(b: &BootstrapDoc) -> String {
    let mut s = format!(
        "\nPosture bootstrap ({} resamples, seed {}; the selection redone on each): the spread of each stiffness over the models chosen, not an interval conditional on one model\n",
        b.resamples, b.seed
    );
    if b.unidentified > 0 {
        s += &format!(
            "  {} left out: their postures cannot identify the model they chose\n",
            count(b.unidentified, "resample")
        );
    }
    s += &format!(
        "  the recommended model exactly: {}\n  {:<12} {:>7} {:>14} {:>14} {:>14}  unit\n",
        pct(Some(b.recommended_share)),
        "parameter",
        "chosen",
        "median",
        "2.5%",
        "97.5%"
    );
    for p in &b.parameters {
        s += &format!(
            "  {:<12} {:>7} {:>14} {:>14} {:>14}  {}\n",
            p.name,
            pct(Some(p.chosen_share)),
            whole(p.median),
            whole(p.percentile_2_5),
            whole(p.percentile_97_5),
            p.unit
        );
    }
    s
}

/// A figure in whole units, `n/a` where the document has `null`.
fn whole(v: Option<f64>) -> String {
    v.map_or("n/a".into(), |v| format!("{v:.0}"))
}

fn pct(v: Option<f64>) -> String {
    v.map_or("n/a".into(), |v| format!("{:.1}%", 100.0 * v))
}

fn row_line(r: &ModelDoc, mark: &str) -> String {
    let what = r.added.clone().unwrap_or_else(|| "(setup's model)".into());
    let fixed = |v: Option<f64>, digits: usize| v.map_or("n/a".into(), |v| format!("{v:.digits$}"));
    format!(
        "{mark:1} {what:<16} {:>3} {:>9} {:>9} {:>5} {:>10} {:>9} {:>9} {:>7} {:>11} {:>8}\n",
        r.parameters,
        pct(Some(r.in_sample_explained)),
        pct(r.held_out_explained),
        fixed(r.held_out_explained_std_error.map(|v| 100.0 * v), 1),
        fixed(r.held_out_rms_delta_b_mm, 4),
        fixed(r.aic, 1),
        fixed(r.bic, 1),
        fixed(r.noise_ratio, 2),
        r.model_check.map_or("n/a", Verdict::short),
        match (r.physical, r.identified) {
            (_, false) => "unident.",
            (true, true) => "yes",
            (false, true) => "no",
        }
    )
}

const HEADER: &str =
    "  added            par in-sample  held out  s.e.  dB RMS mm       AIC       BIC   noise   residuals  all k>0\n";

/// The text report of a comparison's document `doc` (the path, every step, the nested estimate,
/// the candidates dropped from its pool and its bootstrap), and the recommended model's fit.
pub fn text(doc: &CompareDocument, c: &Comparison, setup: &Setup) -> String {
    let mut s =
        String::from("Model comparison: forward selection on the leave-one-posture-out error\n\n");
    if !doc.dropped.is_empty() {
        s += "Candidates left out (the data could never identify them):\n";
        for d in &doc.dropped {
            s += &format!("  {:<16} {}\n", d.name, d.reason);
        }
        s += "\n";
    }
    s += "Selected path (* recommended):\n";
    s += HEADER;
    for r in &doc.models {
        s += &row_line(r, if r.recommended { "*" } else { "" });
    }
    for (k, step) in doc.steps.iter().enumerate() {
        s += &format!(
            "\nStep {}: every candidate added to the model of step {k}\n",
            k + 1
        );
        s += HEADER;
        for r in &step.candidates {
            let chosen = step.chosen.is_some() && r.added == step.chosen;
            s += &row_line(r, if chosen { ">" } else { "" });
        }
    }
    if let Some(n) = &doc.nested {
        let chosen: Vec<String> = (n.chosen.iter())
            .filter(|c| c.folds > 0)
            .map(|c| format!("{} {}/{}", c.name, c.folds, n.parameters.len()))
            .collect();
        s += &format!(
            "\nNested estimate (the whole selection repeated without each posture): held out {} explained (standard error {:.1}, over the postures), RMS delta_b {:.4} mm; chosen: {}\n",
            pct(Some(n.held_out_explained)),
            100.0 * n.held_out_explained_std_error,
            n.rms_delta_b_mm,
            if chosen.is_empty() { "nothing".into() } else { chosen.join(", ") }
        );
    }
    if let Some(b) = &doc.bootstrap {
        s += &bootstrap_text(b);
    }
    if let Some(note) = &doc.nonlinear_separation {
        s += &format!("\nLost motion and load-dependent compliance: {note}\n");
    }
    s += "\nRecommended model fitted to every posture:\n";
    s += &fit_table(&c.recommended_fit);
    s += &model_check(&c.recommended_fit, setup);
    s += &format!("\n{}\n", doc.conclusion);
    s
}

/// The parameters of a fit with 95% intervals, and what the data cannot identify.
pub fn fit_table(f: &Fit) -> String {
    let mut s = format!(
        "  {:<12} {:>14} {:>31}  unit\n",
        "parameter", "stiffness", "95% interval"
    );
    for p in parameter_docs(f) {
        let v = whole(p.stiffness);
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

/// The text report of a model's identification, its document `doc`.
pub fn model_text(report: &Report, doc: &Document, setup: &Setup) -> String {
    let f = &report.fit;
    let mut s = format!(
        "Stiffness of the model's {} from {} ({} rows), {}\n",
        count(f.parameters.len(), "parameter"),
        count(f.postures, "posture"),
        f.rows,
        report.method.name()
    );
    s += &fit_table(f);
    s += &model_check(f, setup);
    if let Some(robust) = &doc.robust {
        s += &format!(
            "{} reweighting: scale {:.4} mm, {} iterations{}, {} below weight 0.5\n",
            robust.loss,
            mm(robust.scale),
            robust.iterations,
            if robust.converged {
                ""
            } else {
                " (not converged)"
            },
            count(robust.down_weighted.len(), "row")
        );
    }
    if let Some(cv) = &doc.cross_validation {
        s += &cross_validation_text(cv);
    }
    if let Some(p) = &doc.prediction {
        s += &text::prediction(p);
    }
    s
}

/// The model check of a fit against the setup's tracker noise, with its verdict.
pub fn model_check(f: &Fit, setup: &Setup) -> String {
    let variance = setup.noise().displacement_variance();
    let (Some(r), Some(p), Some(v)) = (
        f.noise_ratio(variance),
        f.adequacy_p_value(variance),
        f.verdict(variance),
    ) else {
        return "model check: none (no degrees of freedom)\n".into();
    };
    format!(
        "model check: residual std {r:.2} x the tracker noise (chi-square p = {p:.3e}): {}\n",
        text::verdict(v)
    )
}

/// The spread of every parameter over the folds and the held-out explained share (the
/// document's).
fn cross_validation_text(cv: &CrossValidationDoc) -> String {
    let mut s = format!(
        "\ncross-validation: {}, each fitted without its postures and validated on them (Eq. 22)\n  {:<12} {:>14} {:>12} {:>14} {:>14}  unit\n",
        count(cv.folds, "fold"),
        "parameter",
        "mean",
        "std",
        "min",
        "max"
    );
    for p in &cv.spread {
        s += &format!(
            "  {:<12} {:>14} {:>12} {:>14} {:>14}  {}\n",
            p.name,
            whole(p.mean),
            whole(p.std),
            whole(p.min),
            whole(p.max),
            p.unit
        );
    }
    s += &format!(
        "held out: RMS delta_b {:.4} mm of RMS {:.4} mm measured: {:.1}% explained (standard error {:.1}, over the postures)\n",
        mm(cv.rms_delta_b),
        mm(cv.rms_measured),
        cv.explained_pct,
        cv.explained_std_error_pct
    );
    s
}
