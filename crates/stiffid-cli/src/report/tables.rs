//! The report's tables as text cells, rendered by both [`super::html`] and [`super::markdown`].

use super::{criteria_values, CRITERIA};
use stiffid::internal::design::study::{Findings, Study};

/// A table: header and rows of text cells.
pub struct Table {
    /// Column titles.
    pub header: Vec<String>,
    /// Rows, each as long as the header.
    pub rows: Vec<Vec<String>>,
}

fn strings<const N: usize>(cells: [&str; N]) -> Vec<String> {
    cells.iter().map(|s| s.to_string()).collect()
}

/// A number with 4 significant digits (scientific when very large or small).
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return "inf".into();
    }
    match v.abs() {
        a if a != 0.0 && !(1e-3..1e5).contains(&a) => format!("{v:.3e}"),
        _ => format!(
            "{:.*}",
            (3 - v.abs().max(1e-300).log10().floor() as i32).clamp(0, 6) as usize,
            v
        ),
    }
}

/// One row per group: how it was found, the paper's indices, and the measured accuracy.
pub fn groups(study: &Study) -> Table {
    let l = study.validation_level;
    Table {
        header: strings([
            "group",
            "classical",
            "zhang2021",
            "relative_a",
            "average deviation %",
            &format!("worst joint at level {} %", l + 1),
            "search evaluations",
        ]),
        rows: study
            .groups
            .iter()
            .map(|g| {
                let e = &g.evaluation;
                let worst = g.simulation.mean_deviation_pct[l]
                    .iter()
                    .enumerate()
                    .fold((0, 0.0), |b, (j, v)| if *v > b.1 { (j, *v) } else { b });
                vec![
                    g.title.clone(),
                    num(e.classical),
                    num(e.zhang2021),
                    num(e.relative_a),
                    format!("{:.3}", g.average_deviation_pct()),
                    format!("{:.3} (joint {})", worst.1, worst.0 + 1),
                    g.evaluations.to_string(),
                ]
            })
            .collect(),
    }
}

/// The paper's Table 4 at the validation level: mean +- std deviation rate per joint and group.
pub fn table4(study: &Study) -> Table {
    let l = study.validation_level;
    let mut header = vec!["joint".to_string()];
    header.extend(study.groups.iter().map(|g| g.title.clone()));
    Table {
        header,
        rows: (0..6)
            .map(|j| {
                let mut row = vec![(j + 1).to_string()];
                row.extend(study.groups.iter().map(|g| {
                    let s = &g.simulation;
                    format!(
                        "{:.3} ± {:.3} [{:.3}]",
                        s.mean_deviation_pct[l][j],
                        s.std_deviation_pct[l][j],
                        s.predicted_deviation_pct[l][j]
                    )
                }));
                row
            })
            .collect(),
    }
}

/// Every criterion of every group, and Spearman's rho of each against the average deviation rate.
pub fn criteria(study: &Study, findings: &Findings) -> Table {
    let mut header = vec!["criterion".to_string(), "meaning".to_string()];
    header.extend(study.groups.iter().map(|g| g.title.clone()));
    header.push("rho vs accuracy".into());
    let mut rows: Vec<Vec<String>> = CRITERIA
        .iter()
        .enumerate()
        .map(|(c, (key, meaning))| {
            let mut row = vec![key.to_string(), meaning.to_string()];
            row.extend(
                study
                    .groups
                    .iter()
                    .map(|g| num(criteria_values(&g.evaluation)[c].1)),
            );
            row.push(findings.rank_correlation[c].map_or("n/a".into(), |r| format!("{r:+.2}")));
            row
        })
        .collect();
    let mut avg = vec![
        "average deviation %".to_string(),
        "measured, mean over joints and levels".to_string(),
    ];
    avg.extend(
        study
            .groups
            .iter()
            .map(|g| format!("{:.3}", g.average_deviation_pct())),
    );
    avg.push(String::new());
    rows.push(avg);
    Table { header, rows }
}

/// The postures of group `g`, axis angles in degrees.
pub fn postures(study: &Study, g: usize) -> Table {
    Table {
        header: strings([
            "posture", "q1_deg", "q2_deg", "q3_deg", "q4_deg", "q5_deg", "q6_deg",
        ]),
        rows: study.groups[g]
            .postures
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let mut row = vec![(i + 1).to_string()];
                row.extend(q.iter().map(|v| format!("{:.2}", v.to_degrees())));
                row
            })
            .collect(),
    }
}

/// Validation: the true deflection of each test posture and each group's prediction error with its
/// mean identified stiffness (largest over the measuring points).
pub fn validation(study: &Study) -> Table {
    let mut header = vec![
        "test posture (deg)".to_string(),
        "true deflection |delta|, mm (max over points)".to_string(),
    ];
    header.extend(
        study
            .groups
            .iter()
            .map(|g| format!("{}: error, µm", g.title)),
    );
    Table {
        header,
        rows: study
            .setup
            .test_postures()
            .iter()
            .enumerate()
            .map(|(t, q)| {
                let angles: Vec<String> =
                    q.iter().map(|v| format!("{:.2}", v.to_degrees())).collect();
                let max_true = study.test_deflection[t]
                    .iter()
                    .map(|d| d.norm())
                    .fold(0.0, f64::max);
                let mut row = vec![angles.join(", "), format!("{:.4}", max_true * 1e3)];
                row.extend(study.groups.iter().map(|g| {
                    format!(
                        "{:.4}",
                        g.validation_error[t].iter().copied().fold(0.0, f64::max) * 1e6
                    )
                }));
                row
            })
            .collect(),
    }
}

/// The setup in one table: what and value.
pub fn setup(study: &Study) -> Table {
    let s = &study.setup;
    let mm3 = |v: &nalgebra::Vector3<f64>| {
        format!("({:.1}, {:.1}, {:.1})", v.x * 1e3, v.y * 1e3, v.z * 1e3)
    };
    let six = |v: &nalgebra::Vector6<f64>, f: f64| {
        v.iter()
            .map(|x| format!("{:.0}", x * f))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let rows = vec![
        ("setup", s.name().to_string()),
        ("robot", format!("{} ({})", s.robot().name(), s.robot_ref())),
        (
            "springs in",
            format!("{:?} coordinates", s.springs()).to_lowercase(),
        ),
        (
            "true stiffness, Nm/rad",
            s.nominal_stiffness()
                .map_or(NOT_GIVEN.into(), |k| six(k, 1.0)),
        ),
        (
            "loading point (flange frame), mm",
            mm3(&s.tool().loading_point),
        ),
        (
            "measuring points (flange frame), mm",
            s.tool()
                .measuring_points
                .iter()
                .map(mm3)
                .collect::<Vec<_>>()
                .join(" "),
        ),
        (
            "rope load, N / anchor (base frame), mm",
            format!("{} / {}", s.load().load, mm3(&s.load().anchor)),
        ),
        (
            "displacement noise variance sigma^2, mm^2",
            format!("{:.3e}", s.noise().displacement_variance() * 1e6),
        ),
        (
            "noise levels (multiples of sigma^2)",
            s.noise()
                .levels
                .iter()
                .map(|m| m.to_string())
                .collect::<Vec<_>>()
                .join(", "),
        ),
        (
            "bounds lower, deg",
            six(&s.bounds().lower, 180.0 / std::f64::consts::PI),
        ),
        (
            "bounds upper, deg",
            six(&s.bounds().upper, 180.0 / std::f64::consts::PI),
        ),
        (
            "characteristic length L, mm",
            s.characteristic_length()
                .map_or(NOT_GIVEN.into(), |l| format!("{:.0}", l * 1e3)),
        ),
        (
            "Monte Carlo runs per group and level / seed",
            format!("{} / {}", study.runs, study.seed),
        ),
    ];
    Table {
        header: strings(["", "value"]),
        rows: rows
            .into_iter()
            .map(|(a, b)| vec![a.to_string(), b])
            .collect(),
    }
}

/// The start-group check: predicted average deviation rates of the paper's three groups per seed.
pub fn trials(study: &Study) -> Table {
    Table {
        header: strings([
            "start seed",
            "start group %",
            "classical local %",
            "zhang2021 local %",
            "zhang2021 beats both",
        ]),
        rows: study
            .trials
            .iter()
            .map(|t| {
                let [a, b, c] = t.predicted_average_pct;
                vec![
                    t.seed.to_string(),
                    format!("{a:.3}"),
                    format!("{b:.3}"),
                    format!("{c:.3}"),
                    if t.zhang_beats_both() { "yes" } else { "no" }.to_string(),
                ]
            })
            .collect(),
    }
}

/// The paper's Table 4 (`stiffid::internal::design::study::paper_table4`, `[joint][group]`) beside this study's means for
/// Groups 1-3 at the same level.
pub fn paper_table4(study: &Study, paper: &[[f64; 3]; 6]) -> Table {
    let l = study.validation_level;
    let mut header = strings(["joint", "paper Group 1", "paper Group 2", "paper Group 3"]);
    header.extend(
        study
            .groups
            .iter()
            .take(3)
            .map(|g| format!("{}: mean", g.title)),
    );
    Table {
        header,
        rows: (0..6)
            .map(|j| {
                let mut row = vec![(j + 1).to_string()];
                row.extend(paper[j].iter().map(|v| format!("{v:.3}")));
                row.extend(
                    study
                        .groups
                        .iter()
                        .take(3)
                        .map(|g| format!("{:.3}", g.simulation.mean_deviation_pct[l][j])),
                );
                row
            })
            .collect(),
    }
}

/// The value shown for a setup field that is not given.
const NOT_GIVEN: &str = "not given";
