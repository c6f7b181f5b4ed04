//! The text report of `stiffid identify` and its warnings. Numbers that are not finite print as
//! words, never as `NaN` or `inf`.

use stiffid::app::document::{mm, mm3};
use stiffid::app::identify::document::drives::{
    CrossValidation, Document, Intervals, LoadStep, PointOffset, Residual, Robust,
};
use stiffid::app::identify::drives::Report;
use stiffid::app::identify::Fit;
use stiffid::internal::identify::adequacy::{Verdict, SIGNIFICANCE};
use stiffid::internal::io::stiffness::PredictionSection;
use stiffid::internal::robot::kinematics::Coordinates;
use stiffid::Setup;

/// `v` with `decimals` decimals, or `n/a` if it is not finite.
fn num(v: f64, decimals: usize) -> String {
    match v.is_finite() {
        true => format!("{v:.decimals$}"),
        false => "n/a".into(),
    }
}

/// `v` with `decimals` decimals, or `n/a` if it is missing.
fn opt(v: Option<f64>, decimals: usize) -> String {
    v.map_or("n/a".into(), |v| num(v, decimals))
}

/// `v` in scientific notation, or `n/a`.
fn sci(v: f64) -> String {
    match v.is_finite() {
        true => format!("{v:.6e}"),
        false => "n/a".into(),
    }
}

fn joint_list(joints: impl IntoIterator<Item = usize>) -> String {
    let names: Vec<String> = joints.into_iter().map(|j| (j + 1).to_string()).collect();
    match names.len() {
        1 => format!("joint {}", names[0]),
        _ => format!("joints {}", names.join(", ")),
    }
}

/// The text report of `report` and its document `doc`, identified on `setup` (named
/// `setup_name`).
pub fn human(run: &Report, doc: &Document, setup_name: &str, setup: &Setup) -> String {
    let id = &run.identification;
    let springs = match setup.springs() {
        Coordinates::Axis => "axes (drives)",
        Coordinates::Kinematic => "kinematic joints",
    };
    let method = match run.fit {
        Fit::LeastSquares => "least squares (QR)".to_string(),
        Fit::Nonnegative => {
            "least squares with compliances >= 0 (Lawson-Hanson active set on the QR-reduced problem)"
                .to_string()
        }
        Fit::Robust(loss) => format!(
            "robust: iteratively reweighted least squares, {} weights",
            loss.name()
        ),
    };
    let mut s = format!(
        "setup {}, data {}\nsprings on the {springs}; {} rows of Psi from {}; {method}\n\
         cond(Psi) {}, residual RMS {} mm",
        setup_name,
        run.data_name,
        id.rows,
        stiffid::internal::common::words::count(id.postures, "posture"),
        num(id.cond_psi, 4),
        num(mm(doc.residual_rms), 4)
    );
    let Some(u) = &id.uncertainty else {
        s += "\n\njoint  stiffness Nm/rad  compliance rad/Nm\n";
        for j in 0..6 {
            s += &format!(
                "{:>5}  {:>16}  {:>17}\n",
                j + 1,
                num(id.stiffness[j], 0),
                sci(id.compliance[j])
            );
        }
        s += "exactly six rows: the fit is exact and there is no uncertainty estimate\n";
        return s;
    };
    s += &format!(
        ", residual standard deviation s {} mm ({} degrees of freedom, t = {:.4})\n",
        opt(doc.residual_std.map(mm), 4),
        u.dof,
        u.t_quantile
    );
    s += &model_check(run, doc);
    s += "\n95% intervals from the residual variance s^2 (conditional on the model: they cover if it is right):\n";
    if let Some(columns) = Columns::residual(doc) {
        s += &table(doc, columns, doc.poorly_determined);
    }
    s += &bounds_and_physics(doc);
    if let Some(a) = &run.adequacy {
        s += &format!(
            "\n95% intervals from the tracker noise sigma^2 (valid only if the model were exact{}):\n",
            match a.model_error_dominates() {
                true => "; it is not: too narrow",
                false => "",
            }
        );
        if let Some(noise) = &doc.tracker_noise {
            s += &table(doc, Columns::noise(noise), None);
        }
    }
    s += &largest_residuals(&doc.largest_residuals);
    if let Some(robust) = &doc.robust {
        s += &down_weighted(robust);
    }
    if let Some(cv) = &doc.cross_validation {
        s += &cross_validation(doc, cv);
    }
    s += &load_steps(doc.load_steps.as_deref());
    s += &offsets(doc.offsets.as_deref());
    s
}

/// Each posture's linearity, zero-load offset and hysteresis under the load steps (the
/// document's).
fn load_steps(steps: Option<&[LoadStep]>) -> String {
    let Some(steps) = steps else {
        return String::new();
    };
    let opt = |v: Option<f64>, decimals: usize| v.map_or("-".to_string(), |v| num(v, decimals));
    let mark = |flag: bool| if flag { "*" } else { " " };
    let mut s = "
load steps (* beyond the tracker noise, p < 0.01):
                 posture           loads  slope mm/kN  offset mm  R^2        hysteresis mm
"
    .to_string();
    for l in steps {
        s += &format!(
            "{:<16}  {:>5}  {:>11}  {:>9}{} {:<10}{} {:>9}{}
",
            stiffid::internal::common::limits::short(l.posture),
            l.levels,
            opt(l.slope_mm_per_kn, 4),
            opt(l.zero_load_offset.map(mm), 4),
            mark(l.offset_flagged),
            opt(l.r_squared, 6),
            mark(l.nonlinear),
            opt(l.hysteresis.map(mm), 4),
            mark(l.hysteresis_flagged),
        );
    }
    s
}

/// The offsets fitted beside the compliances (the document's).
fn offsets(offsets: Option<&[PointOffset]>) -> String {
    let Some(offsets) = offsets else {
        return String::new();
    };
    let mut s = "
offsets fitted beside the compliances (base frame):
                 posture           point  offset x mm  y mm      z mm
"
    .to_string();
    for o in offsets {
        let [x, y, z] = mm3(&o.offset);
        s += &format!(
            "{:<16}  {:>5}  {:>11}  {:>8}  {:>8}
",
            stiffid::internal::common::limits::short(o.posture),
            o.point,
            num(x, 4),
            num(y, 4),
            num(z, 4),
        );
    }
    s
}

fn model_check(run: &Report, doc: &Document) -> String {
    let Some(a) = &run.adequacy else {
        return String::new();
    };
    let p = match a.p_value {
        p if p < 1e-300 => "< 1e-300".to_string(),
        p => format!("= {p:.3e}"),
    };
    let head = format!(
        "model check: s is {} x the tracker noise sigma = {:.4} mm (chi-square {} with {} degrees of freedom, p {p})",
        num(a.noise_ratio, 2),
        mm(doc.noise_std),
        num(a.chi2, 1),
        a.dof
    );
    match a.verdict() {
        Some(v) => format!("{head}:\n  {}\n", verdict(v)),
        None => format!("{head}\n"),
    }
}

/// The model check's verdict in a sentence.
pub fn verdict(v: Verdict) -> String {
    match v {
        Verdict::ModelError => model_error_dominates(),
        Verdict::BelowNoise => format!("the residuals are far below the tracker noise (lower tail p < {SIGNIFICANCE}): noise-free or simulated data, or the setup's reading_sd_mm is too large; the intervals from the tracker noise are then too wide"),
        Verdict::Consistent => "the residuals are consistent with the tracker noise: the model explains the data as far as the tracker can tell".into(),
    }
}

/// The columns of one table of intervals (the document's, or its `tracker_noise`).
struct Columns<'a> {
    std_error: &'a [Option<f64>; 6],
    percent: &'a [Option<f64>; 6],
    ci95: &'a [[Option<f64>; 2]; 6],
    ci95_from_compliance: &'a [[Option<f64>; 2]; 6],
}

impl<'a> Columns<'a> {
    /// The intervals from the residual variance of `doc` (none without degrees of freedom).
    fn residual(doc: &'a Document) -> Option<Self> {
        Some(Columns {
            std_error: doc.std_error_nm_per_rad.as_ref()?,
            percent: doc.std_error_pct.as_ref()?,
            ci95: doc.ci95_nm_per_rad.as_ref()?,
            ci95_from_compliance: doc.ci95_from_compliance_nm_per_rad.as_ref()?,
        })
    }

    /// The intervals from the tracker noise.
    fn noise(iv: &'a Intervals) -> Self {
        Columns {
            std_error: &iv.std_error_nm_per_rad,
            percent: &iv.std_error_pct,
            ci95: &iv.ci95_nm_per_rad,
            ci95_from_compliance: &iv.ci95_from_compliance_nm_per_rad,
        }
    }
}

/// The stiffness of `doc` with the intervals `iv`, with the poorly determined joints named below
/// if `poor` is given.
fn table(doc: &Document, iv: Columns, poor: Option<[bool; 6]>) -> String {
    let mut s = "joint  stiffness Nm/rad  std error  rel.    95% CI (delta method)    95% CI (1/compliance CI)  compliance rad/Nm\n".to_string();
    for (j, physical) in doc.physical.iter().enumerate() {
        let [a, b] = iv.ci95[j];
        let [c, d] = iv.ci95_from_compliance[j];
        let upper = d.map_or("unbounded".into(), |d| format!("{d:.0}"));
        let lower = c.map_or("none".into(), |c| format!("{c:.0}"));
        s += &format!(
            "{:>5}  {:>16}  {:>9}  {:>5}%  [{:>10}, {:>10}]  [{:>10}, {:>10}]  {:>17}{}\n",
            j + 1,
            opt(doc.stiffness_nm_per_rad[j], 0),
            opt(iv.std_error[j], 0),
            opt(iv.percent[j], 1),
            opt(a, 0),
            opt(b, 0),
            lower,
            upper,
            sci(doc.compliance_rad_per_nm[j]),
            match physical {
                true => "",
                false => "  not physical",
            }
        );
    }
    let poor: Vec<usize> = poor.map_or(Vec::new(), |p| (0..6).filter(|&j| p[j]).collect());
    if !poor.is_empty() {
        s += &format!(
            "poorly determined (std error > {:.0}% of the value): {}; the delta-method interval \
             is unreliable there, trust the 1/compliance interval and measure postures that load these joints more\n",
            doc.poorly_determined_above_pct,
            joint_list(poor)
        );
    }
    s
}

fn bounds_and_physics(doc: &Document) -> String {
    let Some(active) = doc.active_bounds else {
        return String::new();
    };
    match active.iter().any(|a| *a) {
        false => "bounds h >= 0: none active (the same as plain least squares)\n".into(),
        true => format!(
            "bounds h >= 0 active on {}: compliance 0 (infinitely stiff), the data cannot identify these joints\n",
            joint_list((0..6).filter(|&j| active[j]))
        ),
    }
}

/// The document's largest residuals.
fn largest_residuals(largest: &[Residual]) -> String {
    let mut s = "\nlargest residuals (measured - fitted), mm (all of them: --json):\n".to_string();
    for r in largest {
        let [x, y, z] = mm3(&r.residual);
        s += &format!(
            "  line {:>4}  posture {:>4}  point {}  ({x:+.4}, {y:+.4}, {z:+.4})  |{:.4}|\n",
            line(r.line),
            r.posture,
            r.point,
            r.norm_mm
        );
    }
    s
}

/// The document's robust reweighting.
fn down_weighted(robust: &Robust) -> String {
    let shown = 10;
    let rows = &robust.down_weighted;
    let mut s = format!(
        "\nrobust fit: {} weights, c = {}, scale {:.4} mm (1.4826 x median |residual|), {} iterations{}\n\
         down-weighted rows (weight < {}), lowest weight first:\n",
        robust.loss,
        robust.tuning_constant,
        mm(robust.scale),
        robust.iterations,
        if robust.converged { "" } else { " (not converged)" },
        stiffid::internal::identify::robust::DOWN_WEIGHTED
    );
    for row in rows.iter().take(shown) {
        s += &format!(
            "  line {:>4}  posture {:>4}  point {}  {}: weight {:.3}, residual {:+.4} mm\n",
            line(row.line),
            row.posture,
            row.point,
            row.coordinate,
            row.weight,
            mm(row.residual)
        );
    }
    match rows.len() {
        0 => s += "  none\n",
        n if n > shown => s += &format!("  ... and {} more (--json)\n", n - shown),
        _ => {}
    }
    s
}

/// The cross-validation `cv` of the document `doc`.
fn cross_validation(doc: &Document, cv: &CrossValidation) -> String {
    let mut s = format!(
        "\ncross-validation: {} folds{}, each refitted without its postures and validated on them (Eq. 22)\n\
         fold  held-out postures      stiffness Nm/rad (joints 1-6)                                        held-out RMS delta_b mm\n",
        cv.folds,
        match cv.folds == doc.postures {
            true => " (leave one posture out)",
            false => "",
        }
    );
    for (f, fold) in cv.per_fold.iter().enumerate() {
        let labels = &fold.postures;
        let shown = match labels.len() {
            n if n > 3 => format!("{} ... ({n})", labels[..3].join(",")),
            _ => labels.join(","),
        };
        let k: Vec<String> = fold
            .stiffness_nm_per_rad
            .iter()
            .map(|k| format!("{:>10}", opt(*k, 0)))
            .collect();
        s += &format!(
            "{:>4}  {:<20}  {}  {:.4}\n",
            f + 1,
            shown,
            k.join(" "),
            mm(fold.rms_delta_b)
        );
    }
    s += "\nspread across folds:\njoint  full fit Nm/rad  fold mean   fold std  std/full        min         max\n";
    for j in 0..6 {
        s += &format!(
            "{:>5}  {:>15}  {:>9}  {:>9}  {:>7}%  {:>10}  {:>10}\n",
            j + 1,
            opt(doc.stiffness_nm_per_rad[j], 0),
            opt(cv.stiffness_mean_nm_per_rad[j], 0),
            opt(cv.stiffness_std_nm_per_rad[j], 0),
            opt(cv.stiffness_std_pct[j], 1),
            opt(cv.stiffness_min_nm_per_rad[j], 0),
            opt(cv.stiffness_max_nm_per_rad[j], 0)
        );
    }
    s += &format!(
        "held out: RMS delta_b {:.4} mm against measured deflections of RMS {:.4} mm: the model explains {:.1}% (standard error {:.1}, over the postures) of the held-out deflection\n",
        mm(cv.rms_delta_b),
        mm(cv.rms_measured),
        cv.explained_pct,
        cv.explained_std_error_pct
    );
    if let Some(p) = &doc.prediction {
        s += &self::prediction(p);
    }
    s += "influential (removal moves a stiffness by more than its standard error): ";
    match cv.influential_postures.is_empty() {
        true => s += "none\n",
        false => {
            let items: Vec<String> = cv
                .influential_postures
                .iter()
                .map(|i| {
                    let joints = joint_list(i.joints.iter().map(|j| j - 1));
                    format!("{} ({joints})", i.postures.join(","))
                })
                .collect();
            s += &format!("postures {}\n", items.join("; "));
        }
    }
    s
}

/// What the model check's failure means for the intervals.
pub fn model_error_dominates() -> String {
    format!("the model error dominates (p < {SIGNIFICANCE}), not the tracker: the parameter intervals are conditional on the model (a compliance it lacks biases the stiffness, and no interval shows it); the prediction intervals (--cross-validate, then validate, predict, compensate) come from held-out errors and are not")
}

/// The calibration of the prediction intervals (a document's `prediction`), in one line.
pub fn prediction(p: &PredictionSection) -> String {
    let scores: usize = p.folds.iter().map(|f| f.scores.len()).sum();
    let model = p.model_error_pct.map_or(String::new(), |r| {
        format!("; the model's error beyond the noise and the estimate: {r:.1}% of the predicted displacement (the deflection intervals of predict and compensate)")
    });
    format!(
        "prediction intervals ({}, {} held-out coordinates of {}): in the --out file for validate, predict and compensate; 95% of the held-out errors are within {}% of the predicted displacement plus {:.4} mm{model}\n",
        p.method,
        scores,
        stiffid::internal::common::words::count(p.postures, "posture"),
        opt(p.score_q95_pct, 1),
        p.noise_floor_mm
    )
}

/// A measurement's line in its file (`-` for arrays).
fn line(line: Option<u64>) -> String {
    line.map_or("-".into(), |l| l.to_string())
}
