//! A 100 000-block G-code program compensated end to end on the FANUC R-2000iC/165F milling cell
//! (read, process forces, inverse kinematics, compensation, the program written back, as G-code
//! or as a FANUC LS program of Cartesian targets split into sub-programs): the compensate job as
//! `stiffid compensate --program` runs it (goal: under 2 s on 2 cores); and a FANUC LS program of
//! 200 000 joint positions read (each position's number checked against the others by a set:
//! linear in the positions, where a scan of the ones before took about 40 s).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Isometry3;
use stiffid::app::compensate::{self, Input, Request};
use stiffid::internal::machining::compensate::Options;
use stiffid::internal::machining::process::file;
use stiffid::internal::machining::program::generate::Settings;
use stiffid::internal::machining::program::Dialect;
use stiffid::internal::machining::Language;
use stiffid::internal::setup;

/// A raster over 300 mm x 200 mm: 100 rows of 1000 blocks of 0.3 mm, 2 mm apart.
fn raster() -> String {
    let mut s = String::from(
        "(stiffid: tool_rpy_deg = 180 0 0)\nG21 G90\nG0 X-150 Y-100 Z5\nG1 Z-4 F300\n",
    );
    for row in 0..100 {
        let y = -100.0 + 2.0 * row as f64;
        for k in 1..=1000 {
            let x = match row % 2 {
                0 => -150.0 + 0.3 * k as f64,
                _ => 150.0 - 0.3 * k as f64,
            };
            s += &format!("G1 X{x:.3} Y{y:.3}\n");
        }
        s += &format!("G1 Y{:.3}\n", y + 2.0);
    }
    s
}

/// An LS program of `n` joint motions to as many positions.
fn long_ls(n: u32) -> String {
    let mut text = String::from("/PROG  LONG\n/MN\n");
    for i in 1..=n {
        text += &format!("{i:6}:J P[{i}] 100% FINE ;\n");
    }
    text += "/POS\n";
    for i in 1..=n {
        let j1 = f64::from(i % 1000) * 0.01;
        text += &format!("P[{i}]{{\n   GP1:\n\tUF : 0, UT : 1,\n\tJ1= {j1:.3} deg,\tJ2= -16.000 deg,\tJ3= -28.000 deg,\n\tJ4= 3.000 deg,\tJ5= -62.000 deg,\tJ6= 144.000 deg\n}};\n");
    }
    text + "/END\n"
}

fn reading(c: &mut Criterion) {
    let text = long_ls(200_000);
    let mut group = c.benchmark_group("read a program");
    group.sample_size(10);
    group.bench_function("FANUC LS, 200 000 positions", |b| {
        b.iter(|| stiffid::internal::machining::program::parse(&text, Dialect::FanucLs).unwrap())
    });
    group.finish();
}

fn benches(c: &mut Criterion) {
    let builtin = setup::builtin("fanuc-r2000ic-165f").unwrap();
    let s = builtin
        .to_builder()
        .with_tcp(builtin.tool().tcp)
        .with_workpiece(Isometry3::translation(1.3, -0.7, 0.4))
        .build()
        .unwrap();
    let process = file::parse(
        "[tool]\ndiameter_mm = 20\nflutes = 3\nhelix_deg = 30\n[cut]\nfeed_per_tooth_mm = 0.1\n\
         axial_depth_mm = 4\nradial_depth_mm = 10\nmode = \"down\"\n[coefficients]\npreset = \"al7075-t6\"\n",
        "p.toml",
    )
    .unwrap();
    let text = raster();
    let compliance = s.model_compliance("bench").unwrap();
    let mut group = c.benchmark_group("compensate a G-code program");
    group.sample_size(10);
    for (label, output) in [
        ("100 000 blocks, end to end", Language::GCode),
        (
            "100 000 blocks to FANUC LS",
            Language::Robot(Dialect::FanucLs),
        ),
    ] {
        group.bench_function(label, |b| {
            b.iter(|| {
                let request = Request {
                    setup: &s,
                    compliance: compliance.clone(),
                    input: Input::Program {
                        encoding: Default::default(),
                        reading: Default::default(),
                        name: "raster.nc".into(),
                        text: &text,
                        data: None,
                        language: Language::GCode,
                        process_name: "p.toml".into(),
                        process: process.clone(),
                        chord_tolerance: 1e-5,
                        output,
                        out_name: "RST.ls".into(),
                        settings: Settings::default(),
                    },
                    options: Options::for_setup(&s),
                    names: Default::default(),
                };
                compensate::run(request, |_, _, _, _| Ok::<(), stiffid::Error>(())).unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(machining, benches, reading);
criterion_main!(machining);
