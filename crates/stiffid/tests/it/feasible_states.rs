//! The free tool axis keeps to feasible postures: every moved posture it takes keeps the
//! joint-limit margin, the condition number and, with a `[cell]`, clear of the obstacles, checked
//! with the cell's own checker; the path's own posture stays as it is.

use crate::compensate::{line_path, options};
use nalgebra::{Vector3, Vector6};
use stiffid::internal::cell::{capsules, CheckKind, Checker, Part, Thing};
use stiffid::internal::machining::compensate::{self, Compensated, Removed};
use stiffid::internal::robot::kinematics::Coordinates;
use stiffid::internal::robot::presets;
use stiffid::{internal::setup, Setup};

/// The FANUC preset with `cell` appended and its TCP 300 mm off the flange axis (a turn about
/// tool z then swings the flange and the tool's body around the TCP).
fn with_cell(cell: &str) -> Setup {
    let text = setup::builtin_text("fanuc-r2000ic-165f")
        .unwrap()
        .to_string()
        + cell;
    let s = setup::parse(&text, "cell.toml", |r, _| presets::get(r)).unwrap();
    let tcp = Vector3::new(0.3, 0.0, 0.25);
    s.to_builder()
        .with_tcp(tcp)
        .with_loading_point(tcp)
        .build()
        .unwrap()
}

/// Whether posture `q` hits the floor, an obstacle or itself, by the cell's checker.
fn collides(checker: &Checker, q: &Vector6<f64>) -> bool {
    let kinds = [
        CheckKind::Floor,
        CheckKind::Obstacles,
        CheckKind::SelfCollision,
    ];
    (checker.feasibility(q).checks.iter()).any(|c| kinds.contains(&c.kind) && !c.ok)
}

/// The states removed over the path.
fn removed(out: &[Compensated]) -> Removed {
    let mut sum = Removed::default();
    for c in out {
        sum += c.removed;
    }
    sum
}

/// A cell with a box of half-size `half` (m) centred at `centre` (base frame, m).
fn boxed(centre: &Vector3<f64>, half: f64) -> String {
    let (lo, hi) = (
        centre.add_scalar(-half) * 1e3,
        centre.add_scalar(half) * 1e3,
    );
    format!(
        "\n[cell]\nclearance_mm = 10.0\n[[cell.obstacle]]\nname = \"fixture\"\nmin_mm = [{}, {}, {}]\nmax_mm = [{}, {}, {}]\n",
        lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
    )
}

#[test]
fn the_free_tool_axis_never_takes_a_colliding_posture() {
    let free = crate::compensate::rotation(90.0, 3.0);
    let open = with_cell("\n[cell]\nclearance_mm = 10.0\n");
    let path = line_path(&open, 20);
    let compliance = open.model_compliance("test").unwrap();
    let unchecked =
        compensate::path(open.arm(), &compliance, &path, &options(&open, Some(free))).unwrap();
    // The point turned farthest: a box at its tool's flange end, as small as it must be to leave
    // every posture of the path's own clear.
    let (i, far) = (unchecked.iter().enumerate())
        .max_by(|a, b| a.1.tool_rotation.abs().total_cmp(&b.1.tool_rotation.abs()))
        .unwrap();
    assert!(
        far.tool_rotation.abs() > 20f64.to_radians(),
        "{}",
        far.tool_rotation
    );
    let tool = capsules(open.arm(), &open.robot().frames(&far.q))
        .into_iter()
        .find(|c| c.part == Part::Tool)
        .unwrap();
    let own: Vec<Vector6<f64>> = unchecked.iter().map(|c| c.q_before.unwrap()).collect();
    let s = [0.1, 0.05, 0.025]
        .iter()
        .map(|&half| with_cell(&boxed(&tool.a, half)))
        .find(|s| own.iter().all(|q| !collides(&Checker::new(s), q)))
        .expect("a box clear of the path's own postures");
    let checker = Checker::new(&s);
    assert!(
        collides(&checker, &far.q),
        "the box hits the unchecked choice"
    );
    let out = compensate::path(s.arm(), &compliance, &path, &options(&s, Some(free))).unwrap();
    for (k, c) in out.iter().enumerate() {
        assert!(!collides(&checker, &c.q), "point {k} collides");
        let before = c.deflection_before.unwrap().fixed_rows::<3>(0).norm();
        assert!(c.deflection.fixed_rows::<3>(0).norm() <= before * (1.0 + 1e-12));
    }
    assert!(removed(&out).collision > 0, "{:?}", removed(&out));
    assert_ne!(out[i].q, far.q);
}

#[test]
fn every_moved_posture_keeps_the_margin_and_the_condition_number() {
    let s = with_cell("");
    let compliance = s.model_compliance("test").unwrap();
    let path = line_path(&s, 20);
    let free = crate::compensate::rotation(90.0, 3.0);
    let mut o = options(&s, Some(free));
    let loose = compensate::path(s.arm(), &compliance, &path, &o).unwrap();
    // A margin as large as the tightest the free path keeps, plus one degree: some states go.
    let tightest = (loose.iter().filter(|c| c.tool_rotation != 0.0))
        .map(|c| s.robot().limits().distance(&c.q))
        .fold(f64::INFINITY, f64::min);
    o.feasible.margin = tightest + 1f64.to_radians();
    let condition = |q: &Vector6<f64>| {
        let j = s
            .robot()
            .frames(q)
            .jacobian(&s.tool().tcp, Coordinates::Axis);
        let sv = j.singular_values();
        sv.max() / sv.min()
    };
    o.feasible.max_condition = 0.99 * loose.iter().map(|c| condition(&c.q)).fold(1.0, f64::max);
    let out = compensate::path(s.arm(), &compliance, &path, &o).unwrap();
    for (k, c) in out.iter().enumerate() {
        if c.q != c.q_before.unwrap() {
            assert!(
                s.robot().limits().distance(&c.q) >= o.feasible.margin,
                "point {k}"
            );
            assert!(
                condition(&c.q) <= o.feasible.max_condition * (1.0 + 1e-9),
                "point {k}"
            );
        }
    }
    let r = removed(&out);
    assert!(r.limit_margin + r.singularity > 0, "{r:?}");
    assert_eq!(r.collision, 0);
    // A margin no posture keeps: every point stays at the path's own.
    o.feasible.margin = 89f64.to_radians();
    let own = compensate::path(s.arm(), &compliance, &path, &o).unwrap();
    assert!(own.iter().all(|c| c.tool_rotation == 0.0));
    assert!(removed(&own).limit_margin > 0);
}

#[test]
fn the_margin_and_the_condition_number_are_checked() {
    let s = with_cell("");
    let mut o = options(&s, None);
    o.feasible.margin = 91f64.to_radians();
    assert!(o.validate().unwrap_err().to_string().contains("margin_deg"));
    o.feasible.margin = 0.0;
    o.feasible.max_condition = 0.5;
    assert!(o
        .validate()
        .unwrap_err()
        .to_string()
        .contains("max_condition"));
}

/// The stock being cut touching the tool is no collision: with a box around the tool's tip at
/// every posture of the path's own (the tool in the box there), the free tool axis still turns
/// the tool, and every moved posture it takes meets nothing but the stock with the tool.
#[test]
fn the_stock_touching_the_tool_is_not_a_collision() {
    let free = crate::compensate::rotation(90.0, 3.0);
    let open = with_cell("\n[cell]\nclearance_mm = 10.0\n");
    let path = line_path(&open, 20);
    let compliance = open.model_compliance("test").unwrap();
    let turned =
        compensate::path(open.arm(), &compliance, &path, &options(&open, Some(free))).unwrap();
    let tips: Vec<Vector3<f64>> = (turned.iter())
        .map(|c| {
            let frames = open.robot().frames(&c.q_before.unwrap());
            let tool = capsules(open.arm(), &frames).into_iter();
            tool.filter(|c| c.part == Part::Tool)
                .map(|c| c.b)
                .next()
                .unwrap()
        })
        .collect();
    let (lo, hi) = tips.iter().fold(
        (
            Vector3::repeat(f64::INFINITY),
            Vector3::repeat(f64::NEG_INFINITY),
        ),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    );
    let (lo, hi) = (lo.add_scalar(-0.005) * 1e3, hi.add_scalar(0.005) * 1e3);
    let s = with_cell(&format!(
        "\n[cell]\nclearance_mm = 10.0\n[[cell.obstacle]]\nname = \"stock\"\nmin_mm = [{}, {}, {}]\nmax_mm = [{}, {}, {}]\n",
        lo.x, lo.y, lo.z, hi.x, hi.y, hi.z
    ));
    let checker = Checker::new(&s);
    assert!(turned
        .iter()
        .all(|c| collides(&checker, &c.q_before.unwrap())));
    let out = compensate::path(s.arm(), &compliance, &path, &options(&s, Some(free))).unwrap();
    let moved: Vec<&Compensated> = out.iter().filter(|c| c.tool_rotation != 0.0).collect();
    assert!(
        moved.len() >= out.len() / 2,
        "{} of {} moved",
        moved.len(),
        out.len()
    );
    let stock = (Thing::Part(Part::Tool), Thing::Obstacle(0));
    let kinds = [
        CheckKind::Floor,
        CheckKind::Obstacles,
        CheckKind::SelfCollision,
    ];
    for c in moved {
        for m in checker.margins_at(&c.q, &[]) {
            if kinds.contains(&m.kind) && m.margin < 0.0 {
                assert!(
                    m.between == stock || m.between == (stock.1, stock.0),
                    "{m:?}"
                );
            }
        }
    }
}
