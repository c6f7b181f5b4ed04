//! Programs whose G-code has arcs, written with Cartesian targets as KRL `CIRC` moves, run on
//! the simulated true robot of [`crate::true_robot`] as the controller runs them: its nominal
//! inverse kinematics of each target, and of each point of a circle through the start, the via
//! point and the end, the orientation turning from the start's to the end's (KSS `CIRC` with
//! `$ORI_TYPE = #VAR`). Every compensated point of the path, the chord points inside the arcs
//! taken where the commanded circle passes nearest them, lands within 0.05 mm mean of the
//! programmed path, as the straight-line programs do.

use crate::gcode_true_robot::{corpus, prepared, Prepared};
use crate::true_robot::{row, written_with};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use stiffid::internal::machining::program::generate::Targets;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::robot::ik;

/// A motion of the program: to a pose, or on a circle through a via point to a pose (part
/// frame, m).
enum Motion {
    To(Isometry3<f64>),
    Circle(Vector3<f64>, Isometry3<f64>),
}

impl Motion {
    fn end(&self) -> &Isometry3<f64> {
        match self {
            Motion::To(e) | Motion::Circle(_, e) => e,
        }
    }
}

/// The pose of the members of a KRL `E6POS` aggregate's inside (`X .., Y .., .., C ..`), m.
fn e6pos(inner: &str) -> Isometry3<f64> {
    let n = |name: &str| -> f64 {
        (inner.split(',').map(str::trim))
            .find_map(|p| p.strip_prefix(&format!("{name} ")))
            .unwrap()
            .parse()
            .unwrap()
    };
    let r = UnitQuaternion::from_euler_angles(
        n("C").to_radians(),
        n("B").to_radians(),
        n("A").to_radians(),
    );
    let p = Vector3::new(n("X"), n("Y"), n("Z")) * 1e-3;
    Isometry3::from_parts(Translation3::from(p), r)
}

/// The motions of a KRL program, read independently of stiffid's reader: `PTP`, `LIN` and
/// `CIRC` with literal `E6POS` aggregates.
fn motions(krl: &str) -> Vec<Motion> {
    let aggregates = |l: &str| -> Vec<Isometry3<f64>> {
        (l.split("{E6POS:").skip(1))
            .map(|a| e6pos(&a[..a.find('}').unwrap()]))
            .collect()
    };
    (krl.lines())
        .filter_map(|l| {
            let a = aggregates(l);
            match l.split_whitespace().next() {
                Some("PTP" | "LIN") => Some(Motion::To(a[0])),
                Some("CIRC") => Some(Motion::Circle(a[0].translation.vector, a[1])),
                _ => None,
            }
        })
        .collect()
}

/// The point of the circle through `s`, `v`, `e` nearest `p`, and how far along the arc from
/// `s` to `e` it is (0 to 1).
fn on_circle(
    s: &Vector3<f64>,
    v: &Vector3<f64>,
    e: &Vector3<f64>,
    p: &Vector3<f64>,
) -> (Vector3<f64>, f64) {
    let (a, b) = (s - e, v - e);
    let ab = a.cross(&b);
    let centre =
        e + (b * a.norm_squared() - a * b.norm_squared()).cross(&ab) / (2.0 * ab.norm_squared());
    let n = (v - s).cross(&(e - v)).normalize();
    let r = (s - centre).norm();
    let d = p - centre;
    let d = d - n * n.dot(&d);
    let angle = |x: &Vector3<f64>| {
        let (u, x) = (s - centre, x - centre);
        u.cross(&x)
            .dot(&n)
            .atan2(u.dot(&x))
            .rem_euclid(std::f64::consts::TAU)
    };
    let point = centre + d.normalize() * r;
    (point, angle(&point) / angle(e))
}

/// Per compensated point, where the controller running `krl` commands the tool (base frame):
/// a target of the program where the point is one, else the circle's point nearest it.
fn commanded(
    krl: &str,
    part: &Isometry3<f64>,
    compensated: &[Isometry3<f64>],
) -> Vec<Isometry3<f64>> {
    let motions = motions(krl);
    let mut k = 0;
    let mut out = Vec::new();
    for c in compensated {
        let local = part.inverse() * c;
        let at = |m: &Motion| (m.end().translation.vector - local.translation.vector).norm() < 1e-8;
        if k > 0 && at(&motions[k - 1]) {
            out.push(part * motions[k - 1].end());
            continue;
        }
        if at(&motions[k]) {
            out.push(part * motions[k].end());
            k += 1;
            continue;
        }
        let Motion::Circle(v, e) = &motions[k] else {
            panic!("a compensated point off the program's motions: {local:?}");
        };
        let s = motions[k - 1].end();
        let (p, t) = on_circle(
            &s.translation.vector,
            v,
            &e.translation.vector,
            &local.translation.vector,
        );
        let r = s.rotation.slerp(&e.rotation, t);
        out.push(part * Isometry3::from_parts(Translation3::from(p), r));
    }
    assert_eq!(k, motions.len());
    out
}

/// A full circle of radius 10 mm and an arc of 270 deg after it, a finishing pass of the
/// Fusion 360 files' tool 0.02 mm deep and wide ([`finishing`]): under the contour's cut (1 by 3
/// mm) the compensated circles leave the circle by 0.5 mm (the compliance is not the same in
/// every direction of a force turning with the path) and are written as chords.
const CIRCLES: &str = "G90 G94\nG17\nG21\nT1\nS5000 M3\nG54\nG0 X0 Y0\nZ10\nG1 Z5 F1000\nZ-1 F333.3\nG1 X10 F500\nG2 X10 Y0 I-10 J0\nG3 X0 Y-10 I-10 J0\nG1 Y-20\nG0 Z10\nM5\nM30\n";

/// The finishing pass of [`CIRCLES`].
fn finishing() -> String {
    (corpus("process-fusion360.toml"))
        .replace("axial_depth_mm = 1\n", "axial_depth_mm = 0.02\n")
        .replace("radial_depth_mm = 3\n", "radial_depth_mm = 0.02\n")
}

#[test]
fn arcs_written_as_circular_moves_land_on_the_true_robot() {
    let Prepared {
        truth,
        setup,
        compliance,
        frame,
        q0,
        held_rms,
    } = prepared();
    let nominal = crate::true_robot::dh_case().setup.robot().clone();
    let (part, tcp) = (*setup.workpiece().unwrap(), setup.tool().tcp);
    // A Fusion 360 post's contour (32 arcs, 27 within the tolerance once compensated), and a
    // full circle and an arc of 270 deg (two circular moves each).
    for (name, program, process, circles) in [
        (
            "fusion360-personal-arcs.nc",
            corpus("fusion360-personal-arcs.nc"),
            corpus("process-fusion360.toml"),
            27,
        ),
        ("circles.nc", CIRCLES.to_string(), finishing(), 4),
    ] {
        let output = (Language::Robot(Dialect::Krl), Targets::Cartesian);
        let (krl, results) = written_with(&setup, &compliance, (&q0, &program, &process), output);
        let written = krl.matches("\nCIRC {E6POS:").count();
        assert!(written >= circles, "{name}: {written} CIRC");
        let compensated: Vec<Isometry3<f64>> = (results.iter())
            .map(|r| ik::tool_pose(&nominal.frames(&r.q_compensated), &tcp))
            .collect();
        let mut previous = results[0].q;
        let errors: Vec<f64> = (commanded(&krl, &part, &compensated).iter().zip(&results))
            .map(|(target, r)| {
                let q = ik::solve(&nominal, &tcp, target, &previous, &ik::Options::default());
                previous = q.unwrap().q;
                let want = frame.inverse() * Point3::from(r.pose.translation.vector);
                (truth.tcp_at(&previous, &r.wrench) - want.coords).norm()
            })
            .collect();
        let landed = row(&errors);
        eprintln!(
            "{name}: {written} CIRC of {} points; on the true robot: TCP error mean {:.4} mm, max {:.4} mm (held-out RMS {:.4} mm)",
            results.len(),
            landed.mean * 1e3,
            landed.max * 1e3,
            held_rms * 1e3
        );
        assert!(landed.mean <= 0.05e-3, "{name}: {landed:?}");
    }
}
