//! The report figures' own arithmetic (`stiffid-figures`): axis labels, and the calibration's
//! residual histogram and noise densities.

use serde_json::{json, Value};
use stiffid_figures::{calibrate, short, Mark};

#[test]
fn labels_keep_three_significant_digits() {
    assert_eq!(short(0.012345), "0.0123");
    assert_eq!(short(1234.6), "1235");
    assert_eq!(short(2.5), "2.5");
    assert_eq!(short(0.0), "0");
}

/// A calibration document whose fitted readings' residual coordinates are `sin(0.37 k)` (within
/// +-1 mm) and whose estimated and setup noise are both 2 mm: the residuals' figure draws their
/// histogram and the normal densities on +-8 mm (4 sd).
fn residuals_document() -> Value {
    let errors: Vec<Value> = (0..34)
        .map(|i| {
            let c = |k: usize| ((3 * i + k) as f64 * 0.37).sin();
            json!({"set": "fitted", "before_norm_mm": 1.0, "after_norm_mm": 0.5,
                   "after_mm": [c(0), c(1), c(2)]})
        })
        .collect();
    json!({"errors": errors, "noise_std_mm": 2.0, "noise_ratio": 1.0})
}

#[test]
fn a_histogram_is_a_density() {
    let figures = calibrate::figures(&residuals_document()).unwrap();
    let residuals = figures.iter().find(|f| f.name == "residuals").unwrap();
    let [Mark::Bars { bars, .. }, Mark::Line { xy: setup, .. }, Mark::Line { xy: estimated, .. }] =
        residuals.chart.marks.as_slice()
    else {
        panic!("the residuals' bars and two densities");
    };
    let area: f64 = bars.iter().map(|(a, b, d)| (b - a) * d).sum();
    assert!((area - 1.0).abs() < 1e-12, "{area}");
    for d in [setup, estimated] {
        assert_eq!(d.len(), 121);
        assert_eq!((d[0].0, d[120].0), (-8.0, 8.0));
        let peak = d[60].1;
        assert!((peak - 1.0 / (2.0 * (2.0 * std::f64::consts::PI).sqrt())).abs() < 1e-15);
    }
}
