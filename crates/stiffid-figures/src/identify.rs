//! The figures of an identification, from its document (`stiffid identify --json`,
//! `docs/schemas/identify.schema.json`, the six drives' form or a model with virtual springs):
//! each measured displacement coordinate against the predicted one, the parameters' stiffness
//! with their 95% intervals, the residuals' normal QQ plot against the tracker's noise, the stiffness of each cross-validation fold against the full fit's, the held-out
//! scores the prediction intervals are built from, and with `--compare-models` the compared
//! models' held-out shares with their standard errors.

use crate::calibrate::{histogram, list, number, triple};
use crate::chart::{Chart, Mark};
use crate::{colour, short, Figure};
use anyhow::{bail, Result};
use serde_json::Value;
use statrs::distribution::{ContinuousCDF, Normal};

/// Every figure of the identify document `doc` (any of its forms), in report order.
///
/// # Errors
/// When `doc` is not an identify document.
pub fn figures(doc: &Value) -> Result<Vec<Figure>> {
    match doc.get("kind").and_then(Value::as_str) {
        Some("identify-comparison") => return Ok(vec![models(doc)]),
        Some("identify-drives" | "identify-springs") => {}
        kind => bail!("not an identify document: its `kind` is {kind:?}"),
    }
    let mut all = Vec::new();
    all.extend(measured(doc));
    all.extend(parameters(doc));
    all.extend(qq(doc));
    all.extend(folds(doc));
    all.extend(prediction(doc));
    Ok(all)
}

/// Each measured displacement coordinate against the one the fit predicts, with the line where
/// they are equal.
fn measured(doc: &Value) -> Option<Figure> {
    let residuals = list(doc, "residuals");
    let mut series: [Vec<(f64, f64)>; 3] = Default::default();
    for r in residuals {
        let (Some(m), Some(p)) = (triple(r, "measured_mm"), triple(r, "predicted_mm")) else {
            continue;
        };
        for a in 0..3 {
            series[a].push((p[a], m[a]));
        }
    }
    let all = series.iter().flatten();
    let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (x, y)| {
        (a.min(x.min(*y)), b.max(x.max(*y)))
    });
    if !lo.is_finite() {
        return None;
    }
    let mut marks: Vec<Mark> = ["x", "y", "z"]
        .iter()
        .zip(series)
        .enumerate()
        .map(|(a, (name, xy))| Mark::Points {
            label: format!("{name}, base frame"),
            colour: colour(a + 1),
            xy,
        })
        .collect();
    marks.push(Mark::Line {
        label: "measured = predicted".into(),
        colour: colour(0),
        xy: vec![(lo, lo), (hi, hi)],
    });
    Some(Figure {
        name: "measured".into(),
        caption: format!("Each measured displacement coordinate (base frame) against the one the identified model predicts for it, {} measurements: on the line the model explains the measurement; the residual is the vertical distance to it.", residuals.len()),
        chart: Chart {
            title: "Measured against predicted displacement".into(),
            x_desc: "predicted displacement, mm".into(),
            y_desc: "measured displacement, mm".into(),
            log_y: false,
            x_names: Vec::new(),
            marks,
        },
    })
}

/// Each parameter's stiffness with its 95% interval, % of the stiffness: the six drives' form
/// (`ci95_nm_per_rad`) or a model's (`parameters[].ci95`), the parameters named.
fn parameters(doc: &Value) -> Option<Figure> {
    let params = list(doc, "parameters");
    let drives = list(doc, "ci95_nm_per_rad");
    let mut values = Vec::new();
    let mut names = Vec::new();
    for (j, p) in params.iter().enumerate() {
        let k = number(p, "stiffness");
        let ci = p
            .get("ci95")
            .filter(|c| !c.is_null())
            .or_else(|| drives.get(j))
            .and_then(Value::as_array);
        let at = |i: usize| ci.and_then(|c| c.get(i)).and_then(Value::as_f64);
        names.push(
            p.get("name")
                .and_then(Value::as_str)
                .unwrap_or("?")
                .to_string(),
        );
        if let (Some(k), Some(lo), Some(hi)) = (k, at(0), at(1))
            && k != 0.0
        {
            let pct = |v: f64| 100.0 * (v / k - 1.0);
            values.push((j as f64, 0.0, pct(lo), pct(hi)));
        }
    }
    if values.is_empty() {
        return None;
    }
    Some(Figure {
        name: "parameters".into(),
        caption: format!("The 95% interval of each of the {} parameters' stiffness, % of the identified stiffness (each in its unit: Nm/rad for the drives and rotational springs, N/mm for translational ones; the table gives the values). A parameter without a bar is not identified by the data, or its interval is unbounded (the table gives its ends).", params.len()),
        chart: Chart {
            title: "Stiffness of each parameter: 95% interval".into(),
            x_desc: "parameter".into(),
            y_desc: "interval / stiffness - 1, %".into(),
            log_y: false,
            x_names: names,
            marks: vec![Mark::Intervals {
                label: "95% interval around the identified stiffness".into(),
                colour: colour(2),
                values,
            }],
        },
    })
}

/// The residual coordinates over the tracker's noise against the normal quantiles.
fn qq(doc: &Value) -> Option<Figure> {
    let sd = number(doc, "noise_std_mm").filter(|s| *s > 0.0)?;
    let mut z: Vec<f64> = (list(doc, "residuals").iter())
        .filter_map(|r| triple(r, "residual_mm"))
        .flatten()
        .map(|r| r / sd)
        .collect();
    z.sort_by(f64::total_cmp);
    let n = z.len() as f64;
    let normal = Normal::standard();
    let xy: Vec<(f64, f64)> = (z.iter().enumerate())
        .map(|(i, v)| (normal.inverse_cdf((i as f64 + 0.5) / n), *v))
        .collect();
    let ends = xy.first().zip(xy.last()).map(|(a, b)| (a.0, b.0))?;
    let line = |k: f64| vec![(ends.0, k * ends.0), (ends.1, k * ends.1)];
    let mut marks = vec![
        Mark::Points {
            label: "residual coordinates x, y, z".into(),
            colour: colour(2),
            xy,
        },
        Mark::Line {
            label: "the tracker's noise (slope 1)".into(),
            colour: colour(5),
            xy: line(1.0),
        },
    ];
    if let Some(r) = number(doc, "noise_ratio") {
        marks.push(Mark::Line {
            label: format!("the residuals' spread (slope {})", short(r)),
            colour: colour(0),
            xy: line(r),
        });
    }
    Some(Figure {
        name: "qq".into(),
        caption: format!("Normal QQ plot of the residuals (measured minus fitted displacement, every coordinate) over the tracker's noise on a displacement coordinate ({} mm): on the slope-1 line the model explains the data to the noise; steeper is model error, bent ends are outliers.", short(sd)),
        chart: Chart {
            title: "Residuals against the noise (normal QQ)".into(),
            x_desc: "normal quantile".into(),
            y_desc: "residual / noise sd".into(),
            log_y: false,
            x_names: Vec::new(),
            marks,
        },
    })
}

/// Each fold's stiffness per joint relative to the full fit's, %.
fn folds(doc: &Value) -> Option<Figure> {
    let cv = doc.get("cross_validation").filter(|c| !c.is_null())?;
    let full = doc.get("stiffness_nm_per_rad")?.as_array()?;
    let folds = list(cv, "per_fold");
    let n = folds.len().max(1) as f64;
    let mut xy = Vec::new();
    for (f, fold) in folds.iter().enumerate() {
        let k = list(fold, "stiffness_nm_per_rad");
        for j in 0..6 {
            let (Some(a), Some(b)) = (
                k.get(j).and_then(Value::as_f64),
                full.get(j).and_then(Value::as_f64),
            ) else {
                continue;
            };
            let jitter = 0.5 * ((f as f64 + 0.5) / n - 0.5);
            xy.push((j as f64 + jitter, 100.0 * (a / b - 1.0)));
        }
    }
    Some(Figure {
        name: "folds".into(),
        caption: format!("The stability of the cross-validation: each of the {} folds' stiffness per joint, fitted without the fold's postures, against the full fit's, %. A fold far from the others holds an influential posture.", folds.len()),
        chart: Chart {
            title: "Stiffness of each fold against the full fit".into(),
            x_desc: "joint".into(),
            y_desc: "fold / full fit - 1, %".into(),
            log_y: false,
            x_names: (1..=6).map(|j| format!("joint {j}")).collect(),
            marks: vec![Mark::Points {
                label: "one fold".into(),
                colour: colour(2),
                xy,
            }],
        },
    })
}

/// The held-out scores the prediction intervals are built from, with their 95% quantile.
fn prediction(doc: &Value) -> Option<Figure> {
    let p = doc.get("prediction").filter(|p| !p.is_null())?;
    let scores: Vec<f64> = (list(p, "folds").iter())
        .flat_map(|f| list(f, "scores"))
        .filter_map(Value::as_f64)
        .map(|s| 100.0 * s)
        .collect();
    let bars = histogram(&scores);
    let top = bars.iter().map(|b| b.2).fold(0.0, f64::max);
    let mut marks = vec![Mark::Bars {
        label: "held-out scores".into(),
        colour: colour(2),
        bars,
    }];
    let q = number(p, "score_q95_pct");
    if let Some(q) = q {
        marks.push(Mark::Line {
            label: format!("95% quantile: {} %", short(q)),
            colour: colour(5),
            xy: vec![(q, 0.0), (q, top)],
        });
    }
    let floor = number(p, "noise_floor_mm").unwrap_or(0.0);
    Some(Figure {
        name: "prediction".into(),
        caption: format!("The prediction intervals: each held-out coordinate's error |measured - predicted| over |predicted| + {} mm (the noise floor), %. A predicted displacement d is within ±(q95 (|d| + {} mm)) with 95% probability.", short(floor), short(floor)),
        chart: Chart {
            title: "Held-out scores of the prediction intervals".into(),
            x_desc: "score, % of the predicted displacement plus the noise floor".into(),
            y_desc: "density, 1/%".into(),
            log_y: false,
            x_names: Vec::new(),
            marks,
        },
    })
}

/// The compared models' held-out shares with one standard error.
fn models(doc: &Value) -> Figure {
    let models = list(doc, "models");
    let name = |m: &Value| {
        let springs: Vec<&str> = list(m, "springs")
            .iter()
            .filter_map(Value::as_str)
            .collect();
        match m.get("added").and_then(Value::as_str) {
            Some(a) => format!("+ {a}"),
            None if springs.is_empty() => "drives".into(),
            None => springs.join(", "),
        }
    };
    let (mut held, mut chosen) = (Vec::new(), Vec::new());
    for (i, m) in models.iter().enumerate() {
        let Some(e) = number(m, "held_out_explained") else {
            continue;
        };
        let se = number(m, "held_out_explained_std_error").unwrap_or(0.0);
        let v = (i as f64, 100.0 * e, 100.0 * (e - se), 100.0 * (e + se));
        match m.get("recommended").and_then(Value::as_bool) {
            Some(true) => chosen.push(v),
            _ => held.push(v),
        }
    }
    let in_sample = (models.iter().enumerate())
        .filter_map(|(i, m)| Some((i as f64, 100.0 * number(m, "in_sample_explained")?)))
        .collect();
    Figure {
        name: "models".into(),
        caption: "The compared models: the share of the measured displacement each explains in sample and held out (leave-one-posture-out), the held-out share with one standard error; the recommended model in its colour.".into(),
        chart: Chart {
            title: "Compared models: explained share".into(),
            x_desc: "model".into(),
            y_desc: "explained, %".into(),
            log_y: false,
            x_names: models.iter().map(name).collect(),
            marks: vec![
                Mark::Points { label: "in sample".into(), colour: colour(0), xy: in_sample },
                Mark::Intervals { label: "held out, ± 1 standard error".into(), colour: colour(2), values: held },
                Mark::Intervals { label: "held out, the recommended model".into(), colour: colour(5), values: chosen },
            ],
        },
    }
}
