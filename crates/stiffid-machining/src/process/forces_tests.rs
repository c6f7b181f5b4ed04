//! Process forces: the closed-form mean milling force against a numerical integration of the
//! instantaneous chip-thickness model, the slot-milling relations of the mechanistic model, the
//! drilling model, the feed frame and the process file's errors.

use crate::process::milling::{Coefficients, Milling, Mode};
use crate::process::{feed_frame, file, Kind};
use approx::assert_relative_eq;
use nalgebra::Vector3;
use std::f64::consts::PI;
use stiffid_core::Error;

fn coefficients() -> Coefficients {
    Coefficients {
        k_tc: 796e6,
        k_rc: 168.8e6,
        k_ac: 222e6,
        k_te: 27.7e3,
        k_re: 30.8e3,
        k_ae: 1.8e3,
    }
}

fn cut(radial_mm: f64, mode: Mode, helix_deg: f64, flutes: u32) -> Milling {
    Milling {
        diameter: 20e-3,
        flutes,
        helix: helix_deg.to_radians(),
        feed_per_tooth: 0.1e-3,
        axial_depth: 5e-3,
        radial_depth: radial_mm * 1e-3,
        mode,
        coefficients: coefficients(),
        spindle_speed: None,
    }
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre polynomial).
fn gauss(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            loop {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    (p0, p1) = (p1, p2);
                }
                let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-15 {
                    let (mut p0, mut p1) = (1.0, x);
                    for k in 2..=n {
                        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                        (p0, p1) = (p1, p2);
                    }
                    let dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                    return (x, 2.0 / ((1.0 - x * x) * dp * dp));
                }
            }
        })
        .collect()
}

/// `integral of f over [a, b]`, the interval split at `breaks`, 20-point Gauss-Legendre on each
/// piece (the integrand is smooth between the breaks).
fn integrate(f: &dyn Fn(f64) -> Vector3<f64>, a: f64, b: f64, breaks: &[f64]) -> Vector3<f64> {
    let rule = gauss(20);
    let mut points: Vec<f64> = breaks
        .iter()
        .copied()
        .filter(|x| *x > a && *x < b)
        .collect();
    points.push(a);
    points.push(b);
    points.sort_by(f64::total_cmp);
    let mut sum = Vector3::zeros();
    for w in points.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let (mid, half) = ((lo + hi) / 2.0, (hi - lo) / 2.0);
        for &(x, wt) in &rule {
            sum += f(mid + half * x) * (wt * half);
        }
    }
    sum
}

/// The mean force over one revolution, integrated numerically from the instantaneous
/// chip-thickness model written out here from the textbook (not the library's antiderivative):
/// every flute, every height of the edge (Gauss-Legendre over the axial depth), and the spindle
/// angle split where a flute's point enters or leaves the immersion.
fn numerical_mean(m: &Milling) -> Vector3<f64> {
    numerical(m, false)
}

/// [`numerical_mean`] of the moment about the tool tip: each edge element's force `dF` at its
/// point `r = (R sin psi, R cos psi, z)` of the feed frame gives `r x dF`.
fn numerical_mean_moment(m: &Milling) -> Vector3<f64> {
    numerical(m, true)
}

fn numerical(m: &Milling, moment: bool) -> Vector3<f64> {
    let k = &m.coefficients;
    let (st, ex) = m.immersion();
    let n = m.flutes as usize;
    let pitch = 2.0 * PI / n as f64;
    let kb = 2.0 * m.helix.tan() / m.diameter;
    let sign = if m.helix < 0.0 { -1.0 } else { 1.0 };
    let per_length = |psi: f64| {
        let h = m.feed_per_tooth * psi.sin();
        let (t, r, a) = (
            k.k_tc * h + k.k_te,
            k.k_rc * h + k.k_re,
            k.k_ac * h + k.k_ae,
        );
        Vector3::new(
            -t * psi.cos() - r * psi.sin(),
            t * psi.sin() - r * psi.cos(),
            sign * a,
        )
    };
    let at_height = |z: f64| {
        let lag = kb.abs() * z;
        let mut breaks = Vec::new();
        for j in 0..n {
            for edge in [st, ex] {
                breaks.push((edge - j as f64 * pitch + lag).rem_euclid(2.0 * PI));
            }
        }
        let force = |phi: f64| {
            let mut f = Vector3::zeros();
            for j in 0..n {
                let psi = (phi + j as f64 * pitch - lag).rem_euclid(2.0 * PI);
                if psi >= st && psi <= ex {
                    let r = m.diameter / 2.0;
                    let point = Vector3::new(r * psi.sin(), r * psi.cos(), z);
                    f += match moment {
                        true => point.cross(&per_length(psi)),
                        false => per_length(psi),
                    };
                }
            }
            f
        };
        integrate(&force, 0.0, 2.0 * PI, &breaks) / (2.0 * PI)
    };
    let rule = gauss(20);
    let (half, mid) = (m.axial_depth / 2.0, m.axial_depth / 2.0);
    rule.iter()
        .map(|&(x, w)| at_height(mid + half * x) * (w * half))
        .sum()
}

#[test]
fn closed_form_mean_equals_the_integrated_instantaneous_model() {
    for (radial, mode, helix, flutes) in [
        (20.0, Mode::Up, 0.0, 3),
        (20.0, Mode::Down, 30.0, 4),
        (5.0, Mode::Up, 0.0, 2),
        (5.0, Mode::Down, 0.0, 3),
        (8.0, Mode::Up, 30.0, 3),
        (3.0, Mode::Down, 45.0, 4),
        (12.0, Mode::Up, -30.0, 1),
    ] {
        let m = cut(radial, mode, helix, flutes);
        for (closed, numeric) in [
            (m.mean_force(), numerical_mean(&m)),
            (m.mean_moment(), numerical_mean_moment(&m)),
        ] {
            let scale = closed.norm();
            assert!(scale > 0.1, "{closed}");
            for i in 0..3 {
                assert!(
                    (closed[i] - numeric[i]).abs() <= 1e-9 * scale,
                    "{radial} mm {mode:?} {helix} deg {flutes} flutes, component {i}: {} vs {}",
                    closed[i],
                    numeric[i]
                );
            }
        }
    }
}

#[test]
fn slot_milling_mean_force_is_linear_in_the_feed_as_the_mechanistic_relations_say() {
    // Full immersion: F_x = -N a (K_rc c / 4 + K_re / pi), F_y = N a (K_tc c / 4 + K_te / pi),
    // F_z = N a (K_ac c / pi + K_ae / 2) (the relations slot tests identify the coefficients by).
    let m = cut(20.0, Mode::Up, 30.0, 3);
    let k = coefficients();
    let (n, a, c) = (3.0, 5e-3, 0.1e-3);
    let expected = Vector3::new(
        -n * a * (k.k_rc * c / 4.0 + k.k_re / PI),
        n * a * (k.k_tc * c / 4.0 + k.k_te / PI),
        n * a * (k.k_ac * c / PI + k.k_ae / 2.0),
    );
    assert_relative_eq!(m.mean_force(), expected, max_relative = 1e-12);
    // By hand: 0.015 m * (19 900 + 8 817) N/m = 430.76 N normal, -210.4 N along the feed, 119.5 N
    // axial for this 20 mm, 3-flute, 5 mm deep slot at 0.1 mm per tooth.
    assert_relative_eq!(
        expected,
        Vector3::new(-210.36, 430.76, 119.50),
        max_relative = 1e-4
    );
}

#[test]
fn instantaneous_force_without_helix_is_the_sum_over_flutes_and_its_peak_is_found() {
    let m = cut(20.0, Mode::Up, 0.0, 2);
    // One flute at psi = 90 deg (the other at 270 deg, outside the slot's [0, 180]).
    let f = m.force_at(PI / 2.0);
    assert_relative_eq!(f, m.per_length(PI / 2.0) * 5e-3, max_relative = 1e-12);
    // The peak of a two-flute slot without helix is at psi = 90 deg +- the edge terms' shift:
    // no grid point beats the fine search, and it is at least the force at 90 deg.
    let peak = m.peak_force(0.1f64.to_radians());
    assert!(peak.norm() >= f.norm() - 1e-9);
    let coarse = m.peak_force(5f64.to_radians());
    assert!(coarse.norm() <= peak.norm() + 1e-9);
    // With helix the force is smoothed: the peak is below the straight flute's.
    let helical = cut(20.0, Mode::Up, 30.0, 2).peak_force(0.1f64.to_radians());
    assert!(helical.norm() < peak.norm());
}

#[test]
fn drilling_torque_and_thrust_follow_the_specific_energy_model() {
    let text = "kind = \"drilling\"\n[tool]\ndiameter_mm = 10\n[cut]\nfeed_per_rev_mm = 0.2\n\
                [coefficients]\nspecific_energy_n_per_mm2 = 800\nspecific_thrust_n_per_mm2 = 1000\n";
    let process = file::parse(text, "drill.toml").unwrap();
    let Kind::Drilling(d) = &process.operations[0].kind else {
        panic!("drilling expected")
    };
    // T = k_c f D^2 / 8 = 800 * 0.2 * 100 / 8 N mm = 2.0 Nm; F = k_f f D / 2 = 1000 N.
    assert_relative_eq!(d.torque(), 2.0, max_relative = 1e-12);
    assert_relative_eq!(d.thrust(), 1000.0, max_relative = 1e-12);
}

#[test]
fn feed_frame_follows_the_feed_and_the_tool_axis() {
    let down = Vector3::new(0.0, 0.0, -1.0);
    let r = feed_frame(&Vector3::new(3.0, 0.0, 0.5), &down).unwrap();
    assert_relative_eq!(r * Vector3::x(), Vector3::x(), epsilon = 1e-15);
    assert_relative_eq!(r * Vector3::y(), Vector3::y(), epsilon = 1e-15);
    assert_relative_eq!(r * Vector3::z(), Vector3::z(), epsilon = 1e-15);
    let r = feed_frame(&Vector3::new(0.0, -2.0, 0.0), &down).unwrap();
    assert_relative_eq!(r * Vector3::y(), Vector3::x(), epsilon = 1e-15);
    assert!(feed_frame(&Vector3::new(0.0, 0.0, 1.0), &down).is_none());
}

const MILLING: &str = "[tool]\ndiameter_mm = 20\nflutes = 3\nhelix_deg = 30\n[cut]\n\
    feed_per_tooth_mm = 0.1\naxial_depth_mm = 5\nradial_depth_mm = 20\nmode = \"up\"\n\
    [coefficients]\npreset = \"al7075-t6\"\n";

#[test]
fn a_preset_gives_its_published_coefficients_and_fields_override_them() {
    let process = file::parse(MILLING, "p.toml").unwrap();
    let Kind::Milling(m) = &process.operations[0].kind else {
        panic!("milling expected")
    };
    assert_relative_eq!(m.coefficients.k_tc, 767.01e6, max_relative = 1e-12);
    assert_relative_eq!(m.coefficients.k_ae, 0.7e3, max_relative = 1e-12);
    assert_eq!(m.tooth_passing_frequency(), None);
    // 12 000 rpm with three flutes: 200 rev/s, 600 tooth passes per second.
    let turning = MILLING.replace("mode = \"up\"", "mode = \"up\"\nspindle_rpm = 12000");
    let Kind::Milling(t) = &file::parse(&turning, "p.toml").unwrap().operations[0].kind else {
        panic!("milling expected")
    };
    assert_relative_eq!(
        t.tooth_passing_frequency().unwrap(),
        600.0,
        max_relative = 1e-15
    );
    let slow = MILLING.replace("mode = \"up\"", "mode = \"up\"\nspindle_rpm = 0.5");
    let e = file::parse(&slow, "p.toml").unwrap_err().to_string();
    assert!(e.contains("cut.spindle_rpm"), "{e}");
    let text = MILLING.replace(
        "preset = \"al7075-t6\"",
        "preset = \"al7075-t6\"\nk_tc_n_per_mm2 = 800",
    );
    let process = file::parse(&text, "p.toml").unwrap();
    let Kind::Milling(m) = &process.operations[0].kind else {
        panic!("milling expected")
    };
    assert_relative_eq!(m.coefficients.k_tc, 800e6, max_relative = 1e-12);
}

#[test]
fn process_file_errors_name_the_field() {
    let cases = [
        (
            "axial_depth_mm = 5",
            "axial_depth_mm = 0",
            "p.toml: cut.axial_depth_mm",
        ),
        (
            "radial_depth_mm = 20",
            "radial_depth_mm = 21",
            "p.toml: cut.radial_depth_mm",
        ),
        ("flutes = 3", "flutes = 13", "p.toml: tool.flutes"),
        ("helix_deg = 30", "helix_deg = 61", "p.toml: tool.helix_deg"),
        ("mode = \"up\"", "mode = \"sideways\"", "p.toml: cut.mode"),
        (
            "preset = \"al7075-t6\"",
            "preset = \"unobtainium\"",
            "p.toml: coefficients.preset",
        ),
        (
            "preset = \"al7075-t6\"",
            "k_tc_n_per_mm2 = 700",
            "p.toml: coefficients.k_rc_n_per_mm2",
        ),
        (
            "diameter_mm = 20",
            "diameter_mm = nan",
            "p.toml: tool.diameter_mm",
        ),
    ];
    for (from, to, field) in cases {
        let text = MILLING.replace(from, to);
        match file::parse(&text, "p.toml") {
            Err(Error::InvalidField { field: f, .. }) => assert_eq!(f, field, "{to}"),
            other => panic!("{to}: {other:?}"),
        }
    }
    let e = file::parse(&MILLING.replace("flutes", "flute"), "p.toml").unwrap_err();
    assert!(e.to_string().starts_with("p.toml: "), "{e}");
    assert!(e.to_string().contains("flute"), "{e}");
}

#[test]
fn several_operations_are_selected_by_tool_number_or_lines() {
    let text = format!(
        "[[operation]]\nname = \"rough\"\ntool_number = 1\n{}\n\
         [[operation]]\nname = \"drill\"\nkind = \"drilling\"\nlines = [10, 20]\n[operation.tool]\n\
         diameter_mm = 8\n[operation.cut]\nfeed_per_rev_mm = 0.15\n[operation.coefficients]\n\
         specific_energy_n_per_mm2 = 700\nspecific_thrust_n_per_mm2 = 900\n",
        MILLING
            .replace("[tool]", "[operation.tool]")
            .replace("[cut]", "[operation.cut]")
            .replace("[coefficients]", "[operation.coefficients]")
    );
    let process = file::parse(&text, "p.toml").unwrap();
    assert_eq!(process.operations.len(), 2);
    assert_eq!(process.operations[0].selector.tool_number, Some(1));
    assert_eq!(process.operations[1].selector.lines, Some((10, 20)));
    let moved = format!("[workpiece]\nbase_from_part = {{ xyz_mm = [1000, 0, 400] }}\n{text}");
    let e = file::parse(&moved, "p.toml").unwrap_err().to_string();
    assert!(
        e.contains("p.toml: workpiece") && e.contains("setup"),
        "{e}"
    );
    let e = file::parse(&text.replace("[10, 20]", "[20, 10]"), "p.toml").unwrap_err();
    assert!(e.to_string().contains("operation[2].lines"), "{e}");
}

/// A textbook example with its published figures: H. El-Hofy, *Fundamentals of Machining
/// Processes*, 2nd ed., CRC Press 2013 (ISBN 978-1-4665-7702-2), chapter 6 (cutting flat
/// surfaces), the worked slot-milling example on p. 189: a cutter of d = 30 mm with Z = 8 teeth cuts a slot t = 4 mm deep at
/// S_z = 0.1 mm per tooth and f = 120 mm/min in a material of specific cutting force
/// k_s = 1000 N/mm^2; the book finds n = 150 rpm, a mean tangential cutting force F_mt = 1019 N,
/// a cutting speed of 14.13 m/min and a mean cutting power of 0.24 kW. With K_tc = k_s and every
/// other coefficient zero the linear edge-force model is the book's (chip thickness
/// `S_z sin(psi)`, force `k_s b h`): one flute's instantaneous force (the library's
/// [`Milling::force_at`]) is then purely tangential, so eight times its mean magnitude over a
/// revolution is F_mt; and for a slot the closed-form mean force across the feed is `pi / 4` of
/// it (`N a K_tc c / 4` against `N a K_tc c / pi`).
#[test]
fn el_hofy_slot_milling_example_gives_the_published_mean_force_and_power() {
    let teeth = 8.0;
    let one_flute = Milling {
        diameter: 30e-3,
        flutes: 1,
        helix: 0.0,
        feed_per_tooth: 0.1e-3,
        axial_depth: 4e-3,
        radial_depth: 30e-3,
        mode: Mode::Up,
        coefficients: Coefficients {
            k_tc: 1000e6,
            k_rc: 0.0,
            k_ac: 0.0,
            k_te: 0.0,
            k_re: 0.0,
            k_ae: 0.0,
        },
        spindle_speed: None,
    };
    // The spindle speed from the table feed: f / (Z S_z) = 120 / 0.8 = 150 rpm (published).
    let rpm = 120.0 / (teeth * 0.1);
    assert_eq!(rpm, 150.0);
    // Mean over one revolution of the flute's force magnitude: 20-point Gauss-Legendre on the
    // immersion [0, pi] (outside it the flute does not cut).
    let mean_one = integrate(
        &|phi| Vector3::new(one_flute.force_at(phi).norm(), 0.0, 0.0),
        0.0,
        PI,
        &[],
    )
    .x / (2.0 * PI);
    let f_mt = teeth * mean_one;
    assert!(
        (f_mt - 1019.0).abs() < 0.5,
        "F_mt {f_mt} N, published 1019 N"
    );
    let speed_m_per_min = PI * 0.030 * rpm;
    // pi 0.030 m 150 rpm = 14.137 m/min, which the book writes 14.13.
    assert!((speed_m_per_min - 14.13).abs() < 0.01, "{speed_m_per_min}");
    let power_kw = f_mt * speed_m_per_min / 60.0 / 1e3;
    assert!(
        (power_kw - 0.24).abs() < 0.005,
        "N_c {power_kw} kW, published 0.24 kW"
    );
    // The closed-form mean force of the eight-tooth cutter: pi / 4 of F_mt across the feed, none
    // along it (no radial coefficient) or along the axis.
    let cutter = Milling {
        flutes: 8,
        ..one_flute
    };
    let mean = cutter.mean_force();
    assert_relative_eq!(mean.y, f_mt * PI / 4.0, max_relative = 1e-9);
    // The closed-form mean torque about the spindle turns at 150 rpm with the published power.
    let torque = cutter.mean_moment().z;
    let torque_power_kw = torque * rpm * 2.0 * PI / 60.0 / 1e3;
    assert!(
        (torque_power_kw - 0.24).abs() < 0.005,
        "T {torque} Nm: {torque_power_kw} kW, published 0.24 kW"
    );
    assert!(
        mean.x.abs() < 1e-9 * mean.y && mean.z.abs() < 1e-9 * mean.y,
        "{mean}"
    );
}

/// Two operations a program could not tell apart are refused naming both; a drilling operation's
/// milling keys, a single operation's keys beside `[[operation]]` tables and a `lines` of another
/// length than two are refused naming the field.
#[test]
fn ambiguous_operations_and_misplaced_keys_are_refused_naming_them() {
    let milling = MILLING
        .replace("[tool]", "[operation.tool]")
        .replace("[cut]", "[operation.cut]")
        .replace("[coefficients]", "[operation.coefficients]");
    let two =
        |a: &str, b: &str| format!("[[operation]]\n{a}\n{milling}\n[[operation]]\n{b}\n{milling}");
    let cases = [
        (two("name = \"a\"\ntool_number = 1", "name = \"a\"\ntool_number = 2"), "p.toml: operation[2]", "name 'a'"),
        (two("name = \"a\"\ntool_number = 1", "name = \"b\"\ntool_number = 1"), "p.toml: operation[2]", "tool_number = 1"),
        (two("name = \"a\"\nlines = [1, 10]", "name = \"b\"\nlines = [10, 20]"), "p.toml: operation[2]", "overlapping lines [1, 10] and [10, 20]"),
        (two("name = \"a\"\nlines = [1, 2, 3]", "name = \"b\""), "p.toml: operation[1].lines", "[1, 2, 3]"),
        (two("name = \"a\"\nlines = [4]", "name = \"b\""), "p.toml: operation[1].lines", "two line numbers"),
        (format!("tool_number = 3\n{}", two("name = \"a\"", "name = \"b\"\ntool_number = 1")), "p.toml: tool_number", "beside [[operation]]"),
        (
            "kind = \"drilling\"\n[tool]\ndiameter_mm = 10\nflutes = 2\n[cut]\nfeed_per_rev_mm = 0.2\n\
             [coefficients]\nspecific_energy_n_per_mm2 = 800\nspecific_thrust_n_per_mm2 = 1000\n".to_string(),
            "p.toml: tool.flutes",
            "a milling field",
        ),
        (
            "kind = \"drilling\"\n[tool]\ndiameter_mm = 10\n[cut]\nfeed_per_rev_mm = 0.2\n\
             [coefficients]\nspecific_energy_n_per_mm2 = 800\nspecific_thrust_n_per_mm2 = 1000\nk_ae_n_per_mm = 1\n".to_string(),
            "p.toml: coefficients.k_ae_n_per_mm",
            "a milling field",
        ),
    ];
    for (text, field, word) in cases {
        match file::parse(&text, "p.toml") {
            Err(Error::InvalidField { field: f, message }) => {
                assert_eq!(f, field, "{message}");
                assert!(message.contains(word), "{word}: {message}");
            }
            other => panic!("{word}: {other:?}"),
        }
    }
    // Both named in the message; distinct selectors pass.
    let e = file::parse(
        &two("name = \"a\"", "name = \"a\"\ntool_number = 2"),
        "p.toml",
    )
    .unwrap_err();
    assert!(
        e.to_string().contains("operation[1] and operation[2]"),
        "{e}"
    );
    let ok = two(
        "name = \"a\"\nlines = [1, 9]",
        "name = \"b\"\nlines = [10, 20]",
    );
    assert_eq!(file::parse(&ok, "p.toml").unwrap().operations.len(), 2);
    let ok = two("name = \"a\"", "name = \"b\"\ntool_number = 2");
    assert_eq!(file::parse(&ok, "p.toml").unwrap().operations.len(), 2);
}
