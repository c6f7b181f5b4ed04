//! A robot on a linear track: load tests at several stations identify the drives and the
//! carriage's springs (crate::model::Family::Carriage) from measurements that carry the track's
//! position (`e1_mm`), and the comparison of models finds the carriage.

use nalgebra::{DVector, Unit, Vector3, Vector6};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stiffid::internal::identify::svd::fit;
use stiffid::internal::model::Family;
use stiffid::internal::observation::{posture_block, Measurement, Observations};
use stiffid::internal::robot::external::{
    ErrorMotions, ExternalAxes, ExternalAxis, ExternalValues,
};
use stiffid::Setup;

/// The paper's COMAU on a 6 m track along (1, 0.1, 0) with a pitch and a straightness error,
/// its model the drives and the carriage's three springs.
fn on_track() -> (Setup, DVector<f64>) {
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let track = ExternalAxis {
        errors: ErrorMotions::new(vec![[0.0, 1e-4, 0.0, 0.0, 2e-4, 0.0], [0.0; 6]]).unwrap(),
        ..ExternalAxis::linear(
            "track",
            Unit::new_normalize(Vector3::new(1.0, 0.1, 0.0)),
            0.0,
            6.0,
        )
    };
    let robot = paper
        .robot()
        .clone()
        .with_external(Some(ExternalAxes::new(vec![track]).unwrap()));
    let springs = Family::Carriage
        .springs(&robot, &[], Some(3e7), Some(2e7), "test")
        .unwrap();
    assert_eq!(
        springs.iter().map(|s| s.name.as_str()).collect::<Vec<_>>(),
        ["carriage_x", "carriage_rx", "carriage_ry"]
    );
    let setup = paper
        .to_builder()
        .with_robot(robot)
        .with_virtual_springs(springs)
        .build()
        .unwrap();
    let h = setup.model_nominal_compliance().unwrap();
    (setup, h)
}

/// Noise-free measurements at `stations` (m), three random postures and wrenches each.
fn measure(setup: &Setup, h: &DVector<f64>, stations: &[f64], seed: u64) -> Vec<Measurement> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (lo, hi) = (setup.bounds().lower, setup.bounds().upper);
    let mut out = Vec::new();
    for (posture, &s) in stations.iter().flat_map(|s| [s; 3]).enumerate() {
        let q = Vector6::from_fn(|i, _| lo[i] + rng.random_range(0.15..0.85) * (hi[i] - lo[i]));
        let wrench = Vector6::from_fn(|i, _| rng.random_range(-1.0..1.0) * [900.0, 200.0][i / 3]);
        let frames = setup.robot().frames_at(&q, &[s]);
        let d = posture_block(setup.arm(), &frames, &wrench) * h;
        for point in 0..setup.tool().measuring_points.len() {
            out.push(Measurement {
                posture,
                point,
                q,
                e: ExternalValues::new(&[s]).unwrap(),
                wrench,
                displacement: d.fixed_rows::<3>(3 * point).into_owned(),
            });
        }
    }
    out
}

#[test]
fn stations_along_the_track_identify_the_drives_and_the_carriage() {
    let (setup, h) = on_track();
    let data = measure(&setup, &h, &[0.3, 2.0, 4.1, 5.8], 7);
    let obs = Observations::from_measurements(setup.arm(), &data).unwrap();
    let f = fit(&obs, &setup.model().parameters()).unwrap();
    assert_eq!(f.identifiability.rank, 9);
    for j in 0..9 {
        let relative = (f.compliance[j] / h[j] - 1.0).abs();
        assert!(relative < 1e-9, "{}: {relative:e}", f.parameters[j].name);
    }
    // The carriage moves with the track: its springs' axes turn with the carriage's pitch, so
    // the same data read as if the track stood at 0 m fit worse.
    let at_zero: Vec<Measurement> = (data.iter())
        .map(|m| Measurement {
            e: ExternalValues::new(&[0.0]).unwrap(),
            ..m.clone()
        })
        .collect();
    let obs = Observations::from_measurements(setup.arm(), &at_zero).unwrap();
    let wrong = fit(&obs, &setup.model().parameters()).unwrap();
    assert!(
        wrong.rss > 1e6 * f.rss.max(1e-30),
        "{} vs {}",
        wrong.rss,
        f.rss
    );
}

#[test]
fn the_comparison_of_models_finds_the_carriage() {
    let (truth, h) = on_track();
    let data = measure(&truth, &h, &[0.3, 1.5, 3.0, 4.5, 5.8], 11);
    let drives = truth
        .to_builder()
        .with_virtual_springs(Vec::new())
        .build()
        .unwrap();
    let pool = stiffid::internal::identify::compare::pool_by_name(
        &drives,
        &["carriage".into(), "base".into()],
    )
    .unwrap();
    let names: Vec<&str> = pool.candidates.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(&names[..3], ["carriage_x", "carriage_rx", "carriage_ry"]);
    // base_x and base_rx lie on the carriage's lines only when the track runs along x: here it
    // does not, so they stay; base_rz is joint 1's axis and is dropped. Two rotations about
    // horizontal axes through the base's origin span the carriage's two (so do joint 1's tilts,
    // tilt1_x and tilt1_y, about horizontal axes through the same point), so which pair a fit
    // takes is the data's tie: the comparison below offers the tool's springs beside them.
    assert_eq!(names.len(), 8);
    let dropped: Vec<&str> = pool.dropped.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(dropped, ["base_rz"]);
    let others = ["carriage".to_string(), "tool".to_string()];
    let pool = stiffid::internal::identify::compare::pool_by_name(&drives, &others).unwrap();
    let comparison =
        stiffid::internal::identify::compare::compare(&drives, &data, &pool.candidates, false)
            .unwrap();
    let mut chosen: Vec<&str> = (comparison.recommended_springs.iter())
        .map(|s| s.name.as_str())
        .collect();
    chosen.sort();
    assert_eq!(chosen, ["carriage_rx", "carriage_ry", "carriage_x"]);
}

#[test]
fn measurements_with_the_track_are_read_and_checked() {
    let (setup, h) = on_track();
    let data = measure(&setup, &h, &[2.0], 3);
    let mut csv = String::from("posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,e1_mm,fx_n,fy_n,fz_n,mx_nm,my_nm,mz_nm,dx_mm,dy_mm,dz_mm\n");
    for m in &data {
        let q: Vec<String> =
            m.q.iter()
                .map(|v| format!("{:.15}", v.to_degrees()))
                .collect();
        let w: Vec<String> = m.wrench.iter().map(|v| format!("{v:.15}")).collect();
        let d: Vec<String> = m
            .displacement
            .iter()
            .map(|v| format!("{:.15e}", v * 1e3))
            .collect();
        let e = m.e.as_slice()[0] * 1e3;
        csv += &format!(
            "p{},{},{},{e},{},{}\n",
            m.posture,
            m.point + 1,
            q.join(","),
            w.join(","),
            d.join(",")
        );
    }
    let file = stiffid::internal::io::measurements::parse(&csv).unwrap();
    assert!((file.measurements[0].e.as_slice()[0] - 2.0).abs() < 1e-15);
    let obs = Observations::from_measurements(setup.arm(), &file.measurements).unwrap();
    let reference = Observations::from_measurements(setup.arm(), &data).unwrap();
    assert!((&obs.psi - &reference.psi).amax() < 1e-12 * reference.psi.amax());

    let outside = csv.replace(",2000,", ",6500,");
    let file = stiffid::internal::io::measurements::parse(&outside).unwrap();
    let e = Observations::from_measurements(setup.arm(), &file.measurements).unwrap_err();
    assert!(
        e.to_string().contains("e1_mm (track)") && e.to_string().contains("6500"),
        "{e}"
    );

    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    let file = stiffid::internal::io::measurements::parse(&csv).unwrap();
    let e = Observations::from_measurements(paper.arm(), &file.measurements).unwrap_err();
    assert!(e.to_string().contains("no external axes"), "{e}");
}

/// A select request on `setup`: a global search of 6 postures (6 starts, seed 1) at `stations`.
fn at(setup: &Setup, stations: Vec<ExternalValues>) -> stiffid::app::select::Request<'_> {
    stiffid::app::select::Request {
        setup,
        criterion: stiffid::internal::design::Criterion::RelativeA,
        purpose: Default::default(),
        calibration: Default::default(),
        method: stiffid::app::select::Method::Global,
        start: None,
        pool: None,
        postures: 6,
        target_pct: None,
        options: stiffid::internal::design::SearchOptions {
            starts: 6,
            ..Default::default()
        },
        restarts: None,
        distinct: None,
        for_candidates: false,
        candidates: None,
        stations,
        progress: &(),
        out: None,
        report_dir: None,
    }
}

#[test]
fn a_design_on_a_track_keeps_the_best_station() {
    let (setup, _) = on_track();
    let q = Vector6::new(0.3, -0.4, -1.6, 0.5, 0.7, -0.2);
    let moved = setup.at_station(&[4.0]).unwrap();
    assert!(moved.robot().external().is_none());
    assert_eq!(
        moved.robot().frames(&q),
        setup.robot().frames_at(&q, &[4.0])
    );

    let stations: Vec<ExternalValues> = [0.5, 3.0, 5.5]
        .iter()
        .map(|s| ExternalValues::new(&[*s]).unwrap())
        .collect();
    let report = stiffid::app::select::run(&at(&setup, stations.clone())).unwrap();
    let values: Vec<f64> = report.stations.iter().map(|s| s.value).collect();
    let best = (0..3)
        .min_by(|&a, &b| values[a].total_cmp(&values[b]))
        .unwrap();
    assert_eq!(report.station, Some(stations[best]));
    assert_eq!(report.value, values[best]);
    // The rope's anchor stays in the cell: the load, and so the best group, differ by station.
    assert!(
        values.iter().any(|v| (v / values[best] - 1.0).abs() > 1e-3),
        "{values:?}"
    );
    // The station's group is the design of the arm standing there.
    let there = setup.at_station(stations[best].as_slice()).unwrap();
    let alone = stiffid::app::select::run(&at(&there, Vec::new())).unwrap();
    assert_eq!(alone.postures, report.postures);

    let refused = |stations, setup| {
        stiffid::app::select::run(&at(setup, stations))
            .unwrap_err()
            .to_string()
    };
    assert!(refused(Vec::new(), &setup).contains("give 1 to 100 stations"));
    let outside = vec![ExternalValues::new(&[6.5]).unwrap()];
    let e = refused(outside, &setup);
    assert!(e.contains("e1_mm (track)") && e.contains("6500"), "{e}");
    let paper = stiffid::internal::setup::builtin("zhang2021-comau-nj165").unwrap();
    assert!(refused(stations, &paper).contains("no external axes"));
}

/// On a cell whose only external axes are a positioner's (the arm on a fixed base), a design
/// needs no station: the positioner moves the part, never the arm, so the group is the design of
/// the arm with the positioner at its zero, the same as with that station given.
#[test]
fn a_design_on_a_positioner_cell_needs_no_station() {
    let text = include_str!("../../../../examples/track/track-cell.toml");
    let start = text.find("[[external_axis]]\nname = \"track\"").unwrap();
    let end = text.find("# The positioner: e2").unwrap();
    let positioner_only = format!("{}{}", &text[..start], &text[end..]);
    let setup = stiffid::internal::setup::parse(&positioner_only, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap();
    let axes = setup.robot().external().unwrap();
    assert_eq!((axes.len(), axes.carrier_len()), (2, 0));
    let without = stiffid::app::select::run(&at(&setup, Vec::new())).unwrap();
    let zero = vec![ExternalValues::new(&[0.0, 0.0]).unwrap()];
    let with = stiffid::app::select::run(&at(&setup, zero.clone())).unwrap();
    assert_eq!(without.postures, with.postures);
    assert_eq!(without.station, Some(zero[0]));
    // A cell with a carrier still needs its stations: where the arm stands is the design's.
    let (track, _) = on_track();
    let e = stiffid::app::select::run(&at(&track, Vec::new())).unwrap_err();
    assert!(e.to_string().contains("give 1 to 100 stations"), "{e}");
}
