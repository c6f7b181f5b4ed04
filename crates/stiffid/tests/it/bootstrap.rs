//! The posture bootstrap of the model comparison (crate::identify::compare::bootstrap): seeded and
//! independent of the thread count, the true declared spring chosen and its stiffness covered on
//! simulated data, the percentiles by hand, and resamples that cannot identify the model counted.

use crate::candidates::{measure, paper_with, ELBOW};
use std::io::Empty;
use stiffid::app::identify::{run, Options, Report, Request};
use stiffid::app::measurements::Data;
use stiffid::internal::design::random_group;
use stiffid::internal::identify::compare::bootstrap::percentile;
use stiffid::internal::identify::compare::document::BootstrapDoc;
use stiffid::internal::identify::compare::{bootstrap, compare, Bootstrap, Comparison, Resampling};
use stiffid::internal::observation::Measurement;
use stiffid::internal::setup::Setup;

/// A rotation about the x axis of link 2's frame (along the upper arm), declared as a candidate
/// and absent from the truth.
const ABSENT: &str = r#"
[[model.spring]]
name = "upper_x"
kind = "rotation"
link = 2
axis = [1, 0, 0]
point_mm = [500, 0, 0]
nominal_stiffness_nm_per_rad = 4e6
candidate = true
"#;

/// The truth (drives plus the elbow spring), the setup declaring the elbow and `ABSENT` as
/// candidates, and measurements of one group of 15 random postures with the setup's tracker
/// noise, seeded by `seed`.
fn simulated(seed: u64) -> (Setup, Setup, Vec<Measurement>) {
    let truth = paper_with(ELBOW);
    let elbow = ELBOW.replace("rotation\"", "rotation\"\ncandidate = true");
    let declared = paper_with(&format!("{elbow}\n{ABSENT}"));
    let h = truth.model_nominal_compliance().unwrap();
    let postures = random_group(&truth, 15, 20);
    let sigma = truth.noise().displacement_sd();
    let data = measure(&truth, &postures, &h, sigma, seed);
    (truth, declared, data)
}

/// The comparison of `data` over `setup`'s declared candidates and its bootstrap.
fn run_bootstrap(
    setup: &Setup,
    data: &[Measurement],
    resamples: usize,
    seed: u64,
) -> (Comparison, Bootstrap) {
    let candidates = setup.candidate_springs().to_vec();
    let c = compare(setup, data, &candidates, false).unwrap();
    let resampling = Resampling { resamples, seed };
    let b = bootstrap(setup, data, &candidates, &c, resampling, &()).unwrap();
    (c, b)
}

/// The same seed gives the same document, bootstrap included, with one thread and with four.
#[test]
fn the_bootstrap_is_seeded_and_independent_of_the_thread_count() {
    let (_, declared, data) = simulated(0);
    let names = ["declared".to_string()];
    let json = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let report = run(Request::<Empty> {
                    progress: &(),
                    setup_name: "paper".into(),
                    setup: &declared,
                    data: Data::Measurements(data.clone()),
                    options: Options {
                        compare_models: true,
                        candidates: Some(names.to_vec()),
                        bootstrap: Some(40),
                        seed: Some(3),
                        ..Options::default()
                    },
                })
                .unwrap();
                let Report::Comparison(report) = report.report else {
                    panic!("not a comparison")
                };
                serde_json::to_string(&report.document()).unwrap()
            })
    };
    let one = json(1);
    assert!(
        one.contains("\"bootstrap\":{\"resamples\":40,\"seed\":3"),
        "{one}"
    );
    assert_eq!(one, json(4));
    // Another seed draws other resamples.
    let models = |seed| run_bootstrap(&declared, &data, 40, seed).1.models;
    assert_eq!(models(3), models(3));
    assert_ne!(models(3), models(4));
}

/// On twenty seeded noise draws over one group of postures, of the drives plus the declared elbow
/// spring, the bootstrap chooses the elbow in at least 90% of the resamples, its median is within
/// the width of its 2.5..97.5% range of the truth, and that range holds the true stiffness in at
/// least 17 of the 20 (95% nominal: 16 or fewer has probability 1.6%); the declared spring the
/// truth lacks (identifiable: the first step's fit identifies it) is chosen in at most 10%, the
/// drives in every resample. The resampling is of these postures: a new group each time would
/// add the design's variation, which no bootstrap of one group sees.
#[test]
fn the_bootstrap_chooses_the_true_spring_and_covers_its_stiffness() {
    let mut covered = 0;
    for seed in 0..20 {
        let (truth, declared, data) = simulated(seed);
        let (c, b) = run_bootstrap(&declared, &data, 200, seed);
        let absent_row = c.steps[0]
            .candidates
            .iter()
            .find(|r| r.added.as_deref() == Some("upper_x"))
            .unwrap();
        assert!(absent_row.identified);
        assert_eq!(b.unidentified, 0);
        let spread = |name: &str| {
            b.parameters
                .iter()
                .find(|s| c.parameters[s.parameter].name == name)
        };
        for k in ["k1", "k2", "k3", "k4", "k5", "k6"] {
            assert_eq!(spread(k).unwrap().chosen, 200, "seed {seed} {k}");
        }
        let elbow = spread("elbow_z").unwrap();
        let truth_k = 1.0 / truth.model_nominal_compliance().unwrap()[6];
        assert!(elbow.chosen >= 180, "seed {seed}: {}", elbow.chosen);
        assert!(elbow.lower <= elbow.median && elbow.median <= elbow.upper);
        assert!(
            (elbow.median - truth_k).abs() <= elbow.upper - elbow.lower,
            "seed {seed}: median {} for {truth_k}, range [{}, {}]",
            elbow.median,
            elbow.lower,
            elbow.upper
        );
        covered += usize::from(elbow.lower <= truth_k && truth_k <= elbow.upper);
        let absent = spread("upper_x").map_or(0, |s| s.chosen);
        assert!(absent <= 20, "seed {seed}: upper_x chosen {absent} times");
    }
    assert!(covered >= 17, "{covered} of 20 ranges hold the truth");
}

/// Definition 7 by hand: 0-based position `p (n - 1)`, interpolated.
#[test]
fn percentiles_interpolate_between_order_statistics() {
    let x = [10.0, 20.0, 40.0, 80.0];
    assert_eq!(percentile(&x, 0.0), 10.0);
    assert_eq!(percentile(&x, 1.0), 80.0);
    // p (n - 1) = 1.5: halfway between 20 and 40.
    assert_eq!(percentile(&x, 0.5), 30.0);
    // 0.025 * 3 = 0.075: 10 + 0.075 * 10.
    assert!((percentile(&x, 0.025) - 10.75).abs() < 1e-12);
    // 0.975 * 3 = 2.925: 40 + 0.925 * 40.
    assert!((percentile(&x, 0.975) - 77.0).abs() < 1e-12);
    assert_eq!(percentile(&[5.0], 0.975), 5.0);
    assert_eq!(percentile(&[1.0, 3.0, 7.0], 0.5), 3.0);
}

/// The shares and percentiles of five resamples, recomputed by hand from each resample's model.
#[test]
fn the_percentiles_and_shares_by_hand() {
    let (_, declared, data) = simulated(1);
    let (c, b) = run_bootstrap(&declared, &data, 5, 1);
    assert_eq!(b.models.len(), 5);
    let mut exact = c.models[c.recommended].parameter_indices.clone();
    exact.sort_unstable();
    let same = b
        .models
        .iter()
        .flatten()
        .filter(|m| m.iter().map(|x| x.0).collect::<Vec<_>>() == exact)
        .count();
    assert_eq!(b.recommended, same);
    // k2 (index 1) is in every model: five values.
    let mut x: Vec<f64> = b
        .models
        .iter()
        .map(|m| m.as_ref().unwrap().iter().find(|p| p.0 == 1).unwrap().1)
        .collect();
    x.sort_by(f64::total_cmp);
    let s = b.parameters.iter().find(|s| s.parameter == 1).unwrap();
    assert_eq!(s.chosen, 5);
    // 0.025 * 4 = 0.1, 0.5 * 4 = 2, 0.975 * 4 = 3.9.
    assert_eq!(s.median, x[2]);
    assert!((s.lower - (x[0] + 0.1 * (x[1] - x[0]))).abs() <= 1e-9 * x[0]);
    assert!((s.upper - (x[3] + 0.9 * (x[4] - x[3]))).abs() <= 1e-9 * x[4]);
    // The values are the stiffness of each resample's recommended fit, not the data's: they vary.
    assert!(x[4] > x[0]);
    // The document in Nm/rad: the same numbers, a share of the five.
    let doc = bootstrap_doc(&c, &b);
    let k2 = doc.parameters.iter().find(|p| p.name == "k2").unwrap();
    assert_eq!((k2.median, k2.chosen_share), (Some(x[2]), 1.0));
    assert_eq!(doc.recommended_share, same as f64 / 5.0);
}

/// Four postures: a resample that draws fewer than three distinct ones cannot be compared (about
/// a third of them); it is counted, never a panic, and the shares are over the others.
#[test]
fn resamples_that_cannot_identify_the_model_are_counted() {
    let (_, declared, mut data) = simulated(2);
    data.retain(|m| m.posture < 4);
    let (c, b) = run_bootstrap(&declared, &data, 200, 2);
    assert!(
        (30..=190).contains(&b.unidentified),
        "{} unidentified",
        b.unidentified
    );
    let k1 = &b.parameters[0];
    assert_eq!(k1.chosen, b.usable());
    assert_eq!(
        b.models.iter().filter(|m| m.is_none()).count(),
        b.unidentified
    );
    let doc = bootstrap_doc(&c, &b);
    assert_eq!(doc.unidentified, b.unidentified);
    assert_eq!(doc.parameters[0].chosen_share, 1.0);
}

/// The number of resamples is checked: 0 and more than the limit are refused, naming the option.
#[test]
fn the_number_of_resamples_is_limited() {
    for resamples in [0, 2001] {
        let err = Resampling { resamples, seed: 1 }.check().unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("bootstrap: {resamples} resamples: expected 1 to 2000")
        );
    }
    assert!(Resampling {
        resamples: 2000,
        seed: 1
    }
    .check()
    .is_ok());
}

/// The bootstrap reports one unit per resample, in one stage.
#[test]
fn the_bootstrap_reports_each_resample_as_progress() {
    #[derive(Default)]
    struct Heard(std::sync::Mutex<Vec<(String, usize, usize)>>);
    impl stiffid::Progress for Heard {
        fn begin(&self, what: &str, total: usize) {
            self.0.lock().unwrap().push((what.into(), total, 0));
        }
        fn advance(&self, done: usize) {
            let mut stages = self.0.lock().unwrap();
            let last = stages.last_mut().expect("advance inside a stage");
            last.2 = last.2.max(done);
        }
    }
    let (_, declared, data) = simulated(0);
    let heard = Heard::default();
    let request = Request::<Empty> {
        setup: &declared,
        setup_name: "declared".into(),
        progress: &heard,
        data: Data::Measurements(data),
        options: Options {
            compare_models: true,
            candidates: Some(vec!["declared".to_string()]),
            bootstrap: Some(12),
            seed: Some(3),
            ..Options::default()
        },
    };
    stiffid::app::identify::run(request).unwrap();
    let stages = heard.0.into_inner().unwrap();
    assert_eq!(stages, [("bootstrap resamples".to_string(), 12, 12)]);
}

/// The bootstrap's part of the comparison's document.
fn bootstrap_doc(c: &Comparison, b: &Bootstrap) -> BootstrapDoc {
    (c.document("setup", "data", 1e-10, &[], Some(b)).bootstrap).expect("the bootstrap's part")
}
