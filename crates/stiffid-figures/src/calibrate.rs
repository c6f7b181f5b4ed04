//! The figures of a robot calibration, from its document (`stiffid calibrate --json`,
//! `docs/schemas/calibrate.schema.json`): each reading's error before and after, held-out
//! readings marked; the residuals' distribution against the tracker's noise; the fitted
//! parameters' change from nominal with their 95% intervals, one figure per unit.

use crate::chart::{Chart, Mark};
use crate::{colour, Figure};
use anyhow::{Context, Result};
use serde_json::Value;

/// The document's field `key` as a number.
pub(crate) fn number(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

/// The document's field `key` as a list (empty when missing or null).
pub(crate) fn list<'a>(v: &'a Value, key: &str) -> &'a [Value] {
    v.get(key)
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

/// A list of three numbers.
pub(crate) fn triple(v: &Value, key: &str) -> Option<[f64; 3]> {
    let a = v.get(key)?.as_array()?;
    let at = |i: usize| a.get(i).and_then(Value::as_f64);
    Some([at(0)?, at(1)?, at(2)?])
}

/// Every figure of the calibration document `doc`, in report order.
///
/// # Errors
/// When `doc` is not a calibration document (no `errors` list, or one without its fields).
pub fn figures(doc: &Value) -> Result<Vec<Figure>> {
    let errors = doc
        .get("errors")
        .and_then(Value::as_array)
        .context("not a calibration document: no `errors` list")?;
    let mut all = vec![before_after(errors)?, residuals(doc, errors)?];
    all.extend(parameters(doc));
    Ok(all)
}

/// Each reading's error length before and after, logarithmic, held-out readings in their colour.
fn before_after(errors: &[Value]) -> Result<Figure> {
    let mut before = Vec::new();
    let mut after: [Vec<(f64, f64)>; 3] = Default::default();
    const SETS: [&str; 3] = ["fitted", "validation", "cross-validation"];
    for (i, e) in errors.iter().enumerate() {
        let (b, a) = (number(e, "before_norm_mm"), number(e, "after_norm_mm"));
        let (b, a) = b
            .zip(a)
            .context("an error without before_norm_mm, after_norm_mm")?;
        let set = e.get("set").and_then(Value::as_str).unwrap_or_default();
        let k = SETS.iter().position(|s| *s == set).unwrap_or(0);
        before.push((i as f64 + 1.0, b));
        after[k].push((i as f64 + 1.0, a));
    }
    let mut marks = vec![Mark::Points {
        label: "before (nominal robot, tracker registered)".into(),
        colour: plotters::style::RGBColor(150, 150, 150),
        xy: before,
    }];
    let labels = [
        "after, fitted readings",
        "after, held out (--validate)",
        "after, held out by posture (--cross-validate)",
    ];
    for (k, xy) in after.into_iter().enumerate() {
        if !xy.is_empty() {
            marks.push(Mark::Points {
                label: labels[k].into(),
                colour: colour([2, 5, 4][k]),
                xy,
            });
        }
    }
    Ok(Figure {
        name: "errors".into(),
        caption: "Each reading's 3D position error (predicted minus read) before and after the calibration, in the order of the document's `errors`: the fitted readings, then the held-out ones. Logarithmic scale.".into(),
        chart: Chart {
            title: "Error per reading, before and after".into(),
            x_desc: "reading (posture and measuring point, in order)".into(),
            y_desc: "error, mm".into(),
            log_y: true,
            x_names: Vec::new(),
            marks,
        },
    })
}

/// The fitted readings' residual coordinates as a histogram (a density), with the normal
/// densities of the setup's tracker noise and of the noise estimated from the residuals.
fn residuals(doc: &Value, errors: &[Value]) -> Result<Figure> {
    let values: Vec<f64> = (errors.iter())
        .filter(|e| e.get("set").and_then(Value::as_str) == Some("fitted"))
        .filter_map(|e| triple(e, "after_mm"))
        .flatten()
        .collect();
    let estimated = number(doc, "noise_std_mm").filter(|s| *s > 0.0);
    let setup = estimated
        .zip(number(doc, "noise_ratio"))
        .map(|(s, r)| s / r);
    let mut marks = vec![Mark::Bars {
        label: "residual coordinates x, y, z of the fitted readings".into(),
        colour: colour(2),
        bars: histogram(&values),
    }];
    for (sd, label, c) in [
        (setup, "normal, the setup's tracker noise", 5),
        (
            estimated,
            "normal, the noise estimated from the residuals",
            0,
        ),
    ] {
        if let Some(sd) = sd.filter(|s| s.is_finite() && *s > 0.0) {
            marks.push(Mark::Line {
                label: format!("{label} (sd {} mm)", crate::short(sd)),
                colour: colour(c),
                xy: density(sd, (4.0 * sd).max(1.1 * spread(&values))),
            });
        }
    }
    Ok(Figure {
        name: "residuals".into(),
        caption: "The distribution of the calibrated robot's residuals (every coordinate of every fitted reading) against the tracker's noise: bars wider than the noise's curve are model error the calibration does not explain.".into(),
        chart: Chart {
            title: "Residuals against the noise".into(),
            x_desc: "residual coordinate, mm".into(),
            y_desc: "density, 1/mm".into(),
            log_y: false,
            x_names: Vec::new(),
            marks,
        },
    })
}

/// The largest absolute value of `v` (0 for none).
fn spread(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// A histogram of `v` as a density, `(left, right, density)` per bin; about `sqrt(n)` bins
/// (at most 60).
pub(crate) fn histogram(v: &[f64]) -> Vec<(f64, f64, f64)> {
    let finite: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    let (lo, hi) = (finite.iter()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(*x), b.max(*x))
    });
    if finite.is_empty() || hi <= lo {
        return Vec::new();
    }
    let bins = ((finite.len() as f64).sqrt().ceil() as usize).clamp(5, 60);
    let width = (hi - lo) / bins as f64;
    let mut counts = vec![0usize; bins];
    for x in &finite {
        counts[(((x - lo) / width) as usize).min(bins - 1)] += 1;
    }
    let n = finite.len() as f64;
    (counts.iter().enumerate())
        .map(|(k, c)| {
            let a = lo + k as f64 * width;
            (a, a + width, *c as f64 / (n * width))
        })
        .collect()
}

/// The normal density of standard deviation `sd` on `[-half, half]`, 121 points.
pub(crate) fn density(sd: f64, half: f64) -> Vec<(f64, f64)> {
    let norm = 1.0 / (sd * (2.0 * std::f64::consts::PI).sqrt());
    (0..=120)
        .map(|k| {
            let x = -half + 2.0 * half * k as f64 / 120.0;
            (x, norm * (-0.5 * (x / sd).powi(2)).exp())
        })
        .collect()
}

/// One figure per unit (`mm`, `deg`, ...) of the identified parameters with a standard
/// deviation: fitted minus nominal with its 95% interval (1.96 sd).
fn parameters(doc: &Value) -> Vec<Figure> {
    let mut units: Vec<&str> = Vec::new();
    let fitted: Vec<&Value> = (list(doc, "parameters").iter())
        .filter(|p| p.get("identified").and_then(Value::as_bool) == Some(true))
        .filter(|p| number(p, "sd").is_some())
        .collect();
    for p in &fitted {
        let u = p.get("unit").and_then(Value::as_str).unwrap_or_default();
        if !units.contains(&u) {
            units.push(u);
        }
    }
    units
        .into_iter()
        .map(|unit| {
            let these: Vec<&&Value> = (fitted.iter())
                .filter(|p| p.get("unit").and_then(Value::as_str) == Some(unit))
                .collect();
            let values = (these.iter().enumerate())
                .filter_map(|(i, p)| {
                    let d = number(p, "value")? - number(p, "nominal")?;
                    let half = 1.96 * number(p, "sd")?;
                    Some((i as f64, d, d - half, d + half))
                })
                .collect();
            let names = (these.iter())
                .map(|p| p.get("name").and_then(Value::as_str).unwrap_or("?").to_string())
                .collect();
            let stem = unit.replace(|c: char| !c.is_ascii_alphanumeric(), "_");
            Figure {
                name: format!("parameters_{stem}"),
                caption: format!("The identified parameters in {unit}: fitted minus nominal with the 95% interval (1.96 standard deviations). An interval that holds 0 is an error the readings do not show."),
                chart: Chart {
                    title: format!("Fitted minus nominal, {unit}, with 95% intervals"),
                    x_desc: "parameter".into(),
                    y_desc: format!("fitted - nominal, {unit}"),
                    log_y: false,
                    x_names: names,
                    marks: vec![Mark::Intervals {
                        label: String::new(),
                        colour: colour(2),
                        values,
                    }],
                },
            }
        })
        .collect()
}
