//! A 100 000-block G-code program compensated end to end on the FANUC R-2000iC/165F milling cell
//! (read, process forces, inverse kinematics, compensation, the program written back, as G-code
//! or as a FANUC LS program of Cartesian targets split into sub-programs): the compensate job as
//! `stiffid compensate --program` runs it (goal: under 2 s on 2 cores).

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Isometry3;
use stiffid::app::compensate::{self, Input, Request};
use stiffid::machining::compensate::Options;
use stiffid::machining::process::file;
use stiffid::machining::program::generate::Settings;
use stiffid::machining::program::Dialect;
use stiffid::machining::Language;
use stiffid::setup;

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

criterion_group!(machining, benches);
criterion_main!(machining);
