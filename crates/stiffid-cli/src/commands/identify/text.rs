//! The text report of `stiffid identify` and its warnings. Numbers that are not finite print as
//! words, never as `NaN` or `inf`.

use stiffid::app::document::mm;
use stiffid::app::identify::document::{Document, LoadStep, PointOffset, POORLY_DETERMINED};
use stiffid::app::identify::{Fit, Report};
use stiffid::identify::adequacy::{Verdict, SIGNIFICANCE};
use stiffid::identify::{Identification, Uncertainty};
use stiffid::io::stiffness::PredictionSection;
use stiffid::robot::kinematics::Coordinates;
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
        stiffid::common::words::count(id.postures, "posture"),
        num(id.cond_psi, 4),
        num(mm(id.residual_rms), 4)
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
        num(mm(u.residual_variance.sqrt()), 4),
        u.dof,
        u.t_quantile
    );
    s += &model_check(run);
    s += "\n95% intervals from the residual variance s^2 (conditional on the model: they cover if it is right):\n";
    s += &table(id, u, doc.poorly_determined);
    s += &bounds_and_physics(id);
    if let Some(a) = &run.adequacy {
        s += &format!(
            "\n95% intervals from the tracker noise sigma^2 (valid only if the model were exact{}):\n",
            match a.model_error_dominates() {
                true => "; it is not: too narrow",
                false => "",
            }
        );
        s += &table(id, &a.from_noise, None);
    }
    s += &largest_residuals(run);
    if let Some(robust) = &id.robust {
        s += &down_weighted(run, robust);
    }
    if let Some(cv) = &doc.cross_validation {
        s += &cross_validation(run, cv, doc.prediction.as_ref());
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
            stiffid::common::limits::short(&l.posture),
            l.levels,
            opt(l.slope_mm_per_kn, 4),
            opt(l.zero_load_offset_mm, 4),
            mark(l.offset_flagged),
            opt(l.r_squared, 6),
            mark(l.nonlinear),
            opt(l.hysteresis_mm, 4),
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
        let [x, y, z] = o.offset_mm;
        s += &format!(
            "{:<16}  {:>5}  {:>11}  {:>8}  {:>8}
",
            stiffid::common::limits::short(&o.posture),
            o.point,
            num(x, 4),
            num(y, 4),
            num(z, 4),
        );
    }
    s
}

fn model_check(run: &Report) -> String {
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
        mm(a.noise_variance.sqrt()),
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

/// The intervals of `u`, with the poorly determined joints named below if `poor` is given.
fn table(id: &Identification, u: &Uncertainty, poor: Option<[bool; 6]>) -> String {
    let physical = id.physical();
    let mut s = "joint  stiffness Nm/rad  std error  rel.    95% CI (delta method)    95% CI (1/compliance CI)  compliance rad/Nm\n".to_string();
    for (j, physical) in physical.iter().enumerate() {
        let k = id.stiffness[j];
        let rel = u.stiffness_std_error[j] / k.abs();
        let [a, b] = u.stiffness_ci95[j];
        let [c, d] = u.stiffness_ci95_from_compliance[j];
        let upper = match d.is_finite() {
            true => format!("{d:.0}"),
            false => "unbounded".into(),
        };
        let lower = match c.is_finite() {
            true => format!("{c:.0}"),
            false => "none".into(),
        };
        s += &format!(
            "{:>5}  {:>16}  {:>9}  {:>5}%  [{:>10}, {:>10}]  [{:>10}, {:>10}]  {:>17}{}\n",
            j + 1,
            num(k, 0),
            num(u.stiffness_std_error[j], 0),
            num(100.0 * rel, 1),
            num(a, 0),
            num(b, 0),
            lower,
            upper,
            sci(id.compliance[j]),
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
            100.0 * POORLY_DETERMINED,
            joint_list(poor)
        );
    }
    s
}

fn bounds_and_physics(id: &Identification) -> String {
    let Some(active) = id.active_bounds else {
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

fn largest_residuals(run: &Report) -> String {
    let id = &run.identification;
    let n = id.residuals.len() / 3;
    let norm = |i: usize| id.residuals.fixed_rows::<3>(3 * i).norm();
    let mut order: Vec<usize> = (0..n).collect();
    let shown = 5.min(n);
    order.select_nth_unstable_by(shown.saturating_sub(1), |&a, &b| {
        norm(b).total_cmp(&norm(a))
    });
    order.truncate(shown);
    order.sort_by(|&a, &b| norm(b).total_cmp(&norm(a)));
    let mut s = "\nlargest residuals (measured - fitted), mm (all of them: --json):\n".to_string();
    for i in order {
        let r = id.residuals.fixed_rows::<3>(3 * i).map(mm);
        s += &format!(
            "  line {:>4}  posture {:>4}  point {}  ({:+.4}, {:+.4}, {:+.4})  |{:.4}|\n",
            line(run, i),
            run.origin.label(i),
            run.origin.points[i] + 1,
            r.x,
            r.y,
            r.z,
            r.norm()
        );
    }
    s
}

fn down_weighted(run: &Report, fit: &stiffid::identify::RobustFit) -> String {
    let shown = 10;
    let rows = fit.down_weighted();
    let mut s = format!(
        "\nrobust fit: {} weights, c = {}, scale {:.4} mm (1.4826 x median |residual|), {} iterations{}\n\
         down-weighted rows (weight < {}), lowest weight first:\n",
        fit.loss.name(),
        fit.loss.tuning_constant(),
        mm(fit.scale),
        fit.iterations,
        if fit.converged { "" } else { " (not converged)" },
        stiffid::identify::robust::DOWN_WEIGHTED
    );
    for &row in rows.iter().take(shown) {
        let i = row / 3;
        s += &format!(
            "  line {:>4}  posture {:>4}  point {}  {}: weight {:.3}, residual {:+.4} mm\n",
            line(run, i),
            run.origin.label(i),
            run.origin.points[i] + 1,
            ['x', 'y', 'z'][row % 3],
            fit.weights[row],
            mm(run.identification.residuals[row])
        );
    }
    match rows.len() {
        0 => s += "  none\n",
        n if n > shown => s += &format!("  ... and {} more (--json)\n", n - shown),
        _ => {}
    }
    s
}

/// The cross-validation of `run`, its figures from the document's `doc` and `prediction`.
fn cross_validation(
    run: &Report,
    doc: &stiffid::app::identify::document::CrossValidation,
    prediction: Option<&PredictionSection>,
) -> String {
    let Some(cv) = &run.cross_validation else {
        return String::new();
    };
    let postures = run.identification.postures;
    let mut s = format!(
        "\ncross-validation: {} folds{}, each refitted without its postures and validated on them (Eq. 22)\n\
         fold  held-out postures      stiffness Nm/rad (joints 1-6)                                        held-out RMS delta_b mm\n",
        cv.folds.len(),
        match cv.folds.len() == postures {
            true => " (leave one posture out)",
            false => "",
        }
    );
    for (f, fold) in cv.folds.iter().enumerate() {
        let labels = run.origin.labels_of(&fold.postures);
        let shown = match labels.len() {
            n if n > 3 => format!("{} ... ({n})", labels[..3].join(",")),
            _ => labels.join(","),
        };
        let k: Vec<String> = fold
            .stiffness
            .iter()
            .map(|k| format!("{:>10}", num(*k, 0)))
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
        let full = run.identification.stiffness[j];
        s += &format!(
            "{:>5}  {:>15}  {:>9}  {:>9}  {:>7}%  {:>10}  {:>10}\n",
            j + 1,
            num(full, 0),
            num(cv.stiffness_mean[j], 0),
            num(cv.stiffness_std[j], 0),
            opt(doc.stiffness_std_percent[j], 1),
            num(cv.stiffness_range[0][j], 0),
            num(cv.stiffness_range[1][j], 0)
        );
    }
    s += &format!(
        "held out: RMS delta_b {:.4} mm against measured deflections of RMS {:.4} mm: the model explains {:.1}% (standard error {:.1}, over the postures) of the held-out deflection\n",
        mm(cv.rms_delta_b),
        mm(cv.rms_measured),
        100.0 * doc.explained,
        100.0 * cv.explained_std_error
    );
    if let Some(p) = prediction {
        s += &self::prediction(p);
    }
    let influential = &run.influential;
    s += "influential (removal moves a stiffness by more than its standard error): ";
    match influential.is_empty() {
        true => s += "none\n",
        false => {
            let items: Vec<String> = influential
                .iter()
                .map(|(postures, joints)| {
                    let joints = joint_list(joints.iter().copied());
                    format!("{} ({joints})", postures.join(","))
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
    format!(
        "prediction intervals ({}, {} held-out coordinates of {}): in the --out file for validate, predict and compensate; 95% of the held-out errors are within {}% of the predicted displacement plus {:.4} mm\n",
        p.method,
        scores,
        stiffid::common::words::count(p.postures, "posture"),
        opt(p.score_q95.map(|q| 100.0 * q), 1),
        p.noise_floor_mm
    )
}

/// The line of measurement `i` in its file (`-` for arrays).
fn line(run: &Report, i: usize) -> String {
    run.origin
        .lines
        .as_ref()
        .map_or("-".into(), |l| l[i].to_string())
}
