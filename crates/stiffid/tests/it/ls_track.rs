//! LS Cartesian positions with group 1's extended axes (`E1=` in a `GP1` position in Cartesian
//! representation: a robot on a track) read as the same postures in joint representation, the
//! pose in the controller's world with the carriage where `E1` says; compensated alike and
//! written back with their axes.

use nalgebra::{Isometry3, Vector3, Vector6};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::cartesian::flags::ConfigurationData;
use stiffid::internal::machining::program::ls::Config;
use stiffid::internal::machining::program::{Context, Dialect};
use stiffid::internal::machining::{self, Language, Program};
use stiffid::internal::robot::configuration::Configuration;
use stiffid::internal::robot::external::{ExternalAxes, ExternalAxis};
use stiffid::internal::robot::ik;
use stiffid::internal::setup;
use stiffid::Setup;

const PROCESS: &str = "[tool]\ndiameter_mm = 20\nflutes = 3\nhelix_deg = 30\n[cut]\nfeed_per_tooth_mm = 0.1\n\
    axial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n[coefficients]\npreset = \"al7075-t6\"\n";

/// The arm's posture (deg) and the track's positions (mm) of the three targets.
const Q_DEG: [f64; 6] = [10.0, 20.0, -10.0, 5.0, -70.0, 15.0];
const TRACK_MM: [f64; 3] = [1500.0, 1560.0, 1620.0];

/// The FANUC R-2000iC/165F on a 6 m track along x.
fn track_cell() -> Setup {
    let base = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let track = ExternalAxis::linear("track", Vector3::x_axis(), 0.0, 6.0);
    let robot = (base.robot().clone()).with_external(Some(ExternalAxes::new(vec![track]).unwrap()));
    base.to_builder().with_robot(robot).build().unwrap()
}

/// An LS program of three linear motions, each position's `GP1` body from `body(i)`.
fn program(body: impl Fn(usize) -> String) -> String {
    let mut text = String::from("/PROG  TRACK\n/MN\n   1:  ! stiffid: tool_frame = 1 ;\n");
    for i in 1..=3 {
        text += &format!("{:>4}:L P[{i}] 10mm/sec FINE ;\n", i + 1);
    }
    text += "/POS\n";
    for i in 0..3 {
        text += &format!(
            "P[{}]{{\n   GP1:\n\tUF : 0, UT : 1,{}\n}};\n",
            i + 1,
            body(i)
        );
    }
    text + "/END\n"
}

/// `text` read and resolved on `s`, and compensated: the program and the report.
fn compensated(s: &Setup, text: &str) -> (Program, machining::Report) {
    let options = Options::for_setup(s);
    let context = Context::of(s);
    let read = machining::read_in(text, Language::Robot(Dialect::FanucLs), 1e-5, &context).unwrap();
    let read = machining::resolve(&read, s, None, &options)
        .unwrap()
        .into_owned();
    let process = file::parse(PROCESS, "p.toml").unwrap();
    let compliance = s.model_compliance("test").unwrap();
    let report =
        machining::compensate(s.arm(), None, &compliance, &read, &process, &options).unwrap();
    (read, report)
}

/// The targets' axis angles (deg) and external values of a program read.
fn targets(p: &Program) -> Vec<([f64; 6], Vec<Option<f64>>)> {
    let Program::Robot(r) = p else { panic!() };
    r.targets
        .iter()
        .map(|t| (t.q_deg, t.external.clone()))
        .collect()
}

#[test]
fn an_ls_cartesian_position_on_a_track_reads_and_compensates_as_the_joint_one() {
    let s = track_cell();
    let q = Vector6::from(Q_DEG).map(f64::to_radians);
    // The tool's pose in the controller's world, the carriage at E1.
    let world = s.program_world();
    let pose = |e: f64| {
        let carrier = Isometry3::translation(e * 1e-3, 0.0, 0.0);
        world.inverse() * carrier * ik::tool_pose(&s.robot().frames(&q), &s.tool().tcp)
    };
    let config = Config::of(&Configuration::of(s.robot(), &q));
    let cartesian = program(|i| {
        let p = pose(TRACK_MM[i]);
        let t = p.translation.vector * 1e3;
        let (w, pp, r) = p.rotation.euler_angles();
        let [w, pp, r] = [w, pp, r].map(f64::to_degrees);
        format!("\tCONFIG : '{config}',\n\tX = {:.9} mm,\tY = {:.9} mm,\tZ = {:.9} mm,\n\tW = {w:.9} deg,\tP = {pp:.9} deg,\tR = {r:.9} deg,\n\tE1= {:.3}  mm", t.x, t.y, t.z, TRACK_MM[i])
    });
    let joint = program(|i| {
        let j: Vec<String> = (Q_DEG.iter().enumerate())
            .map(|(k, v)| format!("J{}= {v:.3} deg", k + 1))
            .collect();
        format!("\n\t{},\n\tE1= {:.3}  mm", j.join(",\t"), TRACK_MM[i])
    });
    let (read_c, report_c) = compensated(&s, &cartesian);
    let (read_j, report_j) = compensated(&s, &joint);
    for ((qc, ec), (qj, ej)) in targets(&read_c).iter().zip(&targets(&read_j)) {
        assert!(
            (Vector6::from(*qc) - Vector6::from(*qj)).amax() < 1e-7,
            "{qc:?} {qj:?}"
        );
        assert_eq!(ec, ej);
    }
    assert_eq!(targets(&read_c)[2].1, vec![Some(1620.0)]);
    for (c, j) in report_c.results.iter().zip(&report_j.results) {
        assert!((c.q_compensated - j.q_compensated).amax() < 1e-9);
        assert!((c.q_compensated - c.q).amax() > 1e-6, "compensated");
    }
    // Written back: the compensated posture's pose on the carriage where E1 says, E1 as read.
    let written = &report_c.program;
    assert!(written.contains("E1= 1620.000  mm"), "{written}");
    let again = machining::read_in(
        written,
        Language::Robot(Dialect::FanucLs),
        1e-5,
        &Context::of(&s),
    )
    .unwrap();
    let again = machining::resolve(&again, &s, None, &Options::for_setup(&s))
        .unwrap()
        .into_owned();
    for ((q, e), r) in targets(&again).iter().zip(&report_c.results) {
        assert!((Vector6::from(*q) - r.q_compensated.map(f64::to_degrees)).amax() < 1e-6);
        assert_eq!(e.len(), 1);
    }
}
