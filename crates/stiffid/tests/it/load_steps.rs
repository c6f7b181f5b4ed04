//! Raw tracker readings under load steps: displacements from each point's unloaded reading, the
//! linearity, zero-load offset and hysteresis per posture, and the offsets fitted beside the
//! compliances, on readings simulated from the forward model of the paper setup.

use crate::common::{deg, PAPER_POSTURES_DEG};
use nalgebra::{Vector3, Vector6};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use stiffid::app::identify::drives::Report;
use stiffid::app::identify::{self as job, Options, Request};
use stiffid::app::measurements::Data;
use stiffid::internal::observation::stiffness::rope_displacements;
use stiffid::Setup;

/// A simulated campaign: loads (N) applied in order at every posture after the unloaded
/// reading; an offset (mm) along the force added to every loaded reading; a hysteresis (mm,
/// base x) added to every falling one; Gaussian noise of standard deviation `noise_mm` on every
/// coordinate of every reading.
struct Campaign<'a> {
    loads: &'a [f64],
    offset_mm: f64,
    hysteresis_mm: f64,
    noise_mm: f64,
    seed: u64,
}

const HEADER: &str =
    "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,load_n,fx_n,fy_n,fz_n,x_mm,y_mm,z_mm";

impl Campaign<'_> {
    /// The readings file of the campaign on `setup` (true stiffness its nominal).
    fn readings(&self, setup: &Setup) -> String {
        let k = setup.nominal_stiffness().unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        let normal = Normal::new(0.0, self.noise_mm.max(1e-300)).unwrap();
        let mut noise = || match self.noise_mm {
            0.0 => Vector3::zeros(),
            _ => Vector3::from_fn(|_, _| normal.sample(&mut rng)),
        };
        let mut text = format!("{HEADER}\n");
        for (i, q_deg) in PAPER_POSTURES_DEG.iter().enumerate() {
            let frames = setup.robot().frames(&deg(q_deg));
            let rope = setup.rope_wrench(&frames);
            let load = rope.fixed_rows::<3>(0).norm();
            let direction = rope.fixed_rows::<3>(0) / load;
            let unit = rope_displacements(setup, &frames, k);
            for (p, point) in setup.tool().measuring_points.iter().enumerate() {
                let rest = frames.point(point) * 1e3;
                let mut row = |f: f64, shift: Vector3<f64>| {
                    let w: Vector6<f64> = rope * (f / load);
                    let x = rest + unit[p] * (1e3 * f / load) + shift + noise();
                    text += &format!(
                        "P{i},{},{},{},{},{},{},{},{f},{},{},{},{},{},{}\n",
                        p + 1,
                        q_deg[0],
                        q_deg[1],
                        q_deg[2],
                        q_deg[3],
                        q_deg[4],
                        q_deg[5],
                        w[0],
                        w[1],
                        w[2],
                        x.x,
                        x.y,
                        x.z
                    );
                };
                row(0.0, Vector3::zeros());
                let mut top: f64 = 0.0;
                for &f in self.loads {
                    let mut shift = direction * self.offset_mm;
                    if f < top {
                        shift += Vector3::x() * self.hysteresis_mm;
                    }
                    top = top.max(f);
                    row(f, shift);
                }
            }
        }
        text
    }
}

fn identify(setup: &Setup, text: &str, offsets: bool) -> stiffid::Result<Report> {
    let options = Options {
        offsets,
        ..Options::default()
    };
    job::run(Request {
        progress: &(),
        setup_name: "setup".into(),
        setup,
        data: Data::File {
            name: "readings.csv".into(),
            reader: text.as_bytes(),
        },
        options,
    })
    .map(|r| match r.report {
        job::Report::Drives(r) => *r,
        _ => panic!("not the six drives"),
    })
}

fn paper() -> Setup {
    stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap()
}

const RISING_FALLING: [f64; 9] = [
    100.0, 200.0, 300.0, 400.0, 500.0, 400.0, 300.0, 200.0, 100.0,
];

#[test]
fn a_known_offset_and_hysteresis_come_back() {
    let setup = paper();
    let back = |offset_mm: f64, hysteresis_mm: f64| {
        let campaign = Campaign {
            loads: &RISING_FALLING,
            offset_mm,
            hysteresis_mm,
            noise_mm: 0.0,
            seed: 1,
        };
        let report = identify(&setup, &campaign.readings(&setup), false).unwrap();
        let steps = report.load_steps.clone().unwrap();
        assert_eq!(steps.len(), 6);
        for l in &steps {
            assert_eq!((l.levels, l.readings), (5, 4 * 9));
            assert!(
                (l.offset_m.unwrap() - offset_mm * 1e-3).abs() < 1e-12,
                "{l:?}"
            );
            assert!(
                (l.hysteresis_m.unwrap() - hysteresis_mm * 1e-3).abs() < 1e-12,
                "{l:?}"
            );
            assert!((l.r_squared.unwrap() - 1.0).abs() < 1e-9, "{l:?}");
            assert!(l.slope_m_per_n.unwrap() > 1e-7 && !l.nonlinear(), "{l:?}");
        }
        (report, steps)
    };
    // 0.02 mm and 0.01 mm: about the tracker noise (0.0096 mm), within what it explains in one
    // posture (the unloaded reference's error shifts the offset too).
    let (report, steps) = back(0.02, 0.01);
    assert!(steps
        .iter()
        .all(|l| !l.offset_flagged() && !l.hysteresis_flagged()));
    assert!(report
        .warnings
        .iter()
        .all(|w| w.kind.code() != "load-steps"));
    // Five times larger: beyond the noise, flagged, one warning each.
    let (report, steps) = back(0.1, 0.05);
    assert!(steps
        .iter()
        .all(|l| l.offset_flagged() && l.hysteresis_flagged()));
    let messages: Vec<&str> = report
        .warnings
        .iter()
        .filter(|w| w.kind.code() == "load-steps")
        .map(|w| w.message.as_str())
        .collect();
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(
        messages[0].contains("readings.csv: postures 'P0', 'P1'")
            && messages[0].contains("zero-load offset")
    );
    assert!(messages[1].contains("hysteresis"));
}

#[test]
fn offsets_beside_the_compliances_recover_the_stiffness() {
    let setup = paper();
    let truth = *setup.nominal_stiffness().unwrap();
    let campaign = Campaign {
        loads: &RISING_FALLING,
        offset_mm: 0.02,
        hysteresis_mm: 0.0,
        noise_mm: 0.0,
        seed: 1,
    };
    let text = campaign.readings(&setup);
    let with = identify(&setup, &text, true).unwrap();
    let without = identify(&setup, &text, false).unwrap();
    let relative = |r: &Report, j: usize| (r.identification.stiffness[j] / truth[j] - 1.0).abs();
    for j in 0..6 {
        assert!(
            relative(&with, j) < 1e-9,
            "joint {}: {}",
            j + 1,
            relative(&with, j)
        );
    }
    assert!((0..6).any(|j| relative(&without, j) > 1e-3));
    let offsets = with.offsets.as_ref().unwrap();
    assert_eq!(offsets.len(), 6 * 4);
    for o in offsets {
        assert!((o.offset.norm() - 0.02e-3).abs() < 1e-11, "{o:?}");
    }
    // 6 postures x 4 points x 9 loaded readings x 3 rows, minus 6 compliances and 72 offsets.
    let u = with.identification.uncertainty.as_ref().unwrap();
    assert_eq!(u.dof, 6 * 4 * 9 * 3 - 6 - 72);
    assert!(with
        .load_steps
        .as_ref()
        .unwrap()
        .iter()
        .all(|l| !l.nonlinear()));
}

#[test]
fn the_standard_errors_with_offsets_match_a_monte_carlo() {
    let setup = paper();
    let sigma_mm = setup.noise().reading_sd() * 1e3;
    let loads = [100.0, 200.0, 300.0, 400.0, 500.0];
    let runs = 200;
    let mut compliances = Vec::new();
    let mut predicted = Vector6::zeros();
    for seed in 0..runs {
        let campaign = Campaign {
            loads: &loads,
            offset_mm: 0.02,
            hysteresis_mm: 0.0,
            noise_mm: sigma_mm,
            seed,
        };
        let report = identify(&setup, &campaign.readings(&setup), true).unwrap();
        let id = &report.identification;
        compliances.push(id.compliance);
        predicted += report
            .adequacy
            .as_ref()
            .unwrap()
            .from_noise
            .compliance_std_error
            / runs as f64;
    }
    let mean = compliances.iter().sum::<Vector6<f64>>() / runs as f64;
    for j in 0..6 {
        let var = compliances
            .iter()
            .map(|h| (h[j] - mean[j]).powi(2))
            .sum::<f64>()
            / (runs - 1) as f64;
        let ratio = var.sqrt() / predicted[j];
        assert!(
            (ratio - 1.0).abs() < 0.15,
            "joint {}: Monte Carlo / analytic {ratio}",
            j + 1
        );
    }
}

#[test]
fn noise_alone_is_not_flagged() {
    let setup = paper();
    let campaign = Campaign {
        loads: &RISING_FALLING,
        offset_mm: 0.0,
        hysteresis_mm: 0.0,
        noise_mm: setup.noise().reading_sd() * 1e3,
        seed: 7,
    };
    let report = identify(&setup, &campaign.readings(&setup), false).unwrap();
    let steps = report.load_steps.as_ref().unwrap();
    let flagged = steps
        .iter()
        .filter(|l| l.offset_flagged() || l.nonlinear() || l.hysteresis_flagged())
        .count();
    // 18 tests at the 1% level: at most one false alarm expected.
    assert!(flagged <= 1, "{steps:?}");
}

#[test]
fn bad_load_step_files_are_named() {
    let setup = paper();
    let loaded_first = format!("{HEADER}\nA,1,0,0,-90,0,0,0,100,0,0,-100,2000,0,2000\n");
    let e = identify(&setup, &loaded_first, false)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("readings.csv")
            && e.contains("line 2")
            && e.contains("start with the unloaded one"),
        "{e}"
    );
    let one_load = format!(
        "{HEADER}\nA,1,0,0,-90,0,0,0,0,0,0,0,2000,0,2000\nA,1,0,0,-90,0,0,0,100,0,50,-100,2000.1,0,1999.9\n\
         B,1,10,0,-90,0,0,0,0,0,0,0,2000,0,2000\nB,1,10,0,-90,0,0,0,100,50,0,-100,2000.1,0,1999.9\n"
    );
    let e = identify(&setup, &one_load, true).unwrap_err().to_string();
    assert!(e.contains("one load only"), "{e}");
    // A load of 100 N whose force change is 0.1 N: the forces in kN.
    let kn = one_load.replace(",0,50,-100,", ",0,0.05,-0.1,");
    let e = identify(&setup, &kn, false).unwrap_err().to_string();
    assert!(
        e.contains("load_n: line 3: a load of 100 N, but the force change")
            && e.contains("is 0.111803398875 N"),
        "{e}"
    );
    let step = format!("{HEADER}\n").replace("load_n", "load_step")
        + "A,1,0,0,-90,0,0,0,1.5,0,0,0,2000,0,2000\n";
    let e = identify(&setup, &step, false).unwrap_err().to_string();
    assert!(
        e.contains("column 9 (load_step)") && e.contains("not a load step"),
        "{e}"
    );
    let negative = format!("{HEADER}\nA,1,0,0,-90,0,0,0,-5,0,0,0,2000,0,2000\n");
    let e = identify(&setup, &negative, false).unwrap_err().to_string();
    assert!(e.contains("column 9 (load_n)"), "{e}");
    let no_forces =
        "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,load_n,x_mm,y_mm,z_mm\n";
    let e = identify(&setup, no_forces, false).unwrap_err().to_string();
    assert!(e.contains("missing column 'fx_n'"), "{e}");
}

/// The guide's worked example: five load steps of 100 N, a 0.02 mm backlash offset along the
/// load and the paper's tracker noise; the stiffness with and without the offset term beside the
/// truth (printed with `--nocapture`).
#[test]
fn worked_example_with_and_without_the_offset_term() {
    let setup = paper();
    let truth = *setup.nominal_stiffness().unwrap();
    let campaign = Campaign {
        loads: &[100.0, 200.0, 300.0, 400.0, 500.0],
        offset_mm: 0.02,
        hysteresis_mm: 0.0,
        noise_mm: setup.noise().reading_sd() * 1e3,
        seed: 1,
    };
    let text = campaign.readings(&setup);
    let with = identify(&setup, &text, true).unwrap();
    let without = identify(&setup, &text, false).unwrap();
    println!("joint  truth Nm/rad  with offsets (error %, 95% interval)  without (error %)");
    let mut worst = [0.0f64; 2];
    for j in 0..6 {
        let error = |r: &Report| 100.0 * (r.identification.stiffness[j] / truth[j] - 1.0);
        let ci = with
            .identification
            .uncertainty
            .as_ref()
            .unwrap()
            .stiffness_ci95[j];
        println!(
            "{}  {:>10.0}  {:>10.0} ({:+.2} %, {:.0}..{:.0})  {:>10.0} ({:+.2} %)",
            j + 1,
            truth[j],
            with.identification.stiffness[j],
            error(&with),
            ci[0],
            ci[1],
            without.identification.stiffness[j],
            error(&without)
        );
        worst = [
            worst[0].max(error(&with).abs()),
            worst[1].max(error(&without).abs()),
        ];
        let se = with
            .identification
            .uncertainty
            .as_ref()
            .unwrap()
            .stiffness_std_error[j];
        assert!((with.identification.stiffness[j] - truth[j]).abs() < 4.0 * se);
    }
    let flagged = without
        .load_steps
        .as_ref()
        .unwrap()
        .iter()
        .filter(|l| l.offset_flagged());
    println!(
        "worst error {:.2} % with offsets, {:.2} % without; offset flagged in {} of 6 postures; noise ratio {:.2} with, {:.2} without",
        worst[0],
        worst[1],
        flagged.count(),
        with.adequacy.as_ref().unwrap().noise_ratio,
        without.adequacy.as_ref().unwrap().noise_ratio
    );
    // Without the offset term the residuals exceed the tracker noise (the model check fails);
    // with it they do not.
    assert!(without.adequacy.as_ref().unwrap().model_error_dominates());
    assert!(!with.adequacy.as_ref().unwrap().model_error_dominates());
}

#[test]
fn offsets_with_a_robust_nonnegative_or_cross_validated_fit_are_refused_saying_why() {
    let setup = paper();
    let campaign = Campaign {
        loads: &RISING_FALLING,
        offset_mm: 0.02,
        hysteresis_mm: 0.0,
        noise_mm: 0.0,
        seed: 1,
    };
    let text = campaign.readings(&setup);
    let run = |options: Options| {
        job::run(Request {
            progress: &(),
            setup_name: "setup".into(),
            setup: &setup,
            data: Data::File {
                name: "readings.csv".into(),
                reader: text.as_bytes(),
            },
            options: Options {
                offsets: true,
                ..options
            },
        })
        .unwrap_err()
        .to_string()
    };
    let huber = run(Options {
        robust: Some(stiffid::internal::identify::robust::Loss::Huber),
        ..Options::default()
    });
    assert!(
        huber.starts_with("offsets: not with robust: the offsets are eliminated by centring"),
        "{huber}"
    );
    let nnls = run(Options {
        nonnegative: true,
        ..Options::default()
    });
    assert!(
        nnls.starts_with("offsets: not with nonnegative: the non-negative fit's standard errors"),
        "{nnls}"
    );
    let loo = run(Options {
        cross_validate: true,
        ..Options::default()
    });
    assert!(
        loo.starts_with("offsets: not with cross_validate: a held-out posture's offsets"),
        "{loo}"
    );
    let folds = run(Options {
        folds: Some(3),
        ..Options::default()
    });
    assert!(
        folds.starts_with("offsets: not with folds: a held-out posture's offsets"),
        "{folds}"
    );
}

/// Each step reads what the last wrote: the readings under load steps that `identify` reads
/// (`load_n` and the force columns) are read by `validate` and `identify --compare-models` too,
/// turned into the same displacements: noise-free readings of the nominal stiffness validate
/// to round-off against it, and the comparison finds the six drives' stiffness again.
#[test]
fn validate_and_the_model_comparison_read_load_step_readings() {
    let setup = paper();
    let text = Campaign {
        loads: &[250.0, 500.0],
        offset_mm: 0.0,
        hysteresis_mm: 0.0,
        noise_mm: 0.0,
        seed: 1,
    }
    .readings(&setup);
    let compliance = setup.model_compliance("test").unwrap();
    let report = stiffid::app::validate::run(stiffid::app::validate::Request {
        setup_name: "setup".into(),
        setup: &setup,
        compliance: &compliance,
        data: Data::File {
            name: "readings.csv".into(),
            reader: text.as_bytes(),
        },
        level: None,
    })
    .unwrap();
    let v = &report.validation;
    assert_eq!(
        v.checks.len(),
        2 * PAPER_POSTURES_DEG.len() * setup.tool().measuring_points.len()
    );
    assert!(v.max < 1e-10, "{} m", v.max);
    assert!(v.measured[0] > 1e-4);
    let drives = identify(&setup, &text, false).unwrap();
    let compared = job::run(Request {
        progress: &(),
        setup_name: "setup".into(),
        setup: &setup,
        data: Data::File {
            name: "readings.csv".into(),
            reader: text.as_bytes(),
        },
        options: Options {
            compare_models: true,
            candidates: Some(vec!["tilt3_x".into()]),
            ..Options::default()
        },
    })
    .unwrap();
    let job::Report::Comparison(c) = compared.report else {
        panic!("not the comparison")
    };
    let k = setup.nominal_stiffness().unwrap();
    for j in 0..6 {
        let identified = drives.identification.stiffness[j];
        assert!((identified - k[j]).abs() < 1e-6 * k[j], "{j}: {identified}");
    }
    assert!(!c.comparison.models.is_empty());
}

/// The share of `runs` seeded campaigns (loads rising then falling, no offset, the setup's
/// tracker noise) whose 95% interval of each joint's compliance holds the true compliance, the
/// six joints pooled; the intervals from the fit's residual variance (`uncertainty`) and from
/// the tracker noise (`adequacy.from_noise`).
fn coverage(setup: &Setup, runs: u64) -> (f64, f64) {
    let sigma_mm = setup.noise().reading_sd() * 1e3;
    let truth = setup.nominal_stiffness().unwrap().map(|k| 1.0 / k);
    let (mut residual, mut noise) = (0usize, 0usize);
    let inside = |ci: &[[f64; 2]; 6], j: usize| ci[j][0] <= truth[j] && truth[j] <= ci[j][1];
    for seed in 0..runs {
        let campaign = Campaign {
            loads: &RISING_FALLING,
            offset_mm: 0.0,
            hysteresis_mm: 0.0,
            noise_mm: sigma_mm,
            seed: 1000 + seed,
        };
        let report = identify(setup, &campaign.readings(setup), false).unwrap();
        let u = report.identification.uncertainty.as_ref().unwrap();
        let n = &report.adequacy.as_ref().unwrap().from_noise;
        residual += (0..6).filter(|&j| inside(&u.compliance_ci95, j)).count();
        noise += (0..6).filter(|&j| inside(&n.compliance_ci95, j)).count();
    }
    let total = 6.0 * runs as f64;
    (residual as f64 / total, noise as f64 / total)
}

#[test]
fn the_intervals_include_the_shared_unloaded_reading() {
    // Nine loaded readings of a point share its unloaded reading: their errors are correlated
    // (covariance sigma^2 (I + J)). Over 200 seeds (1200 intervals, the binomial standard
    // deviation of the share 0.6%), the 95% intervals cover 93-97% of the true compliances.
    let (residual, noise) = coverage(&paper(), 200);
    for (name, share) in [("residual", residual), ("noise", noise)] {
        assert!(
            (0.93..=0.97).contains(&share),
            "{name} intervals cover {share} (residual {residual}, noise {noise})"
        );
    }
}
