//! The calibrated robot, and the files that carry it: a robot TOML file (the DH table with
//! Hayati's `beta_deg`, the axis map, base and flange) and a URDF with corrected joint origins.
//!
//! The calibrated chain is [`ErrorModel::robot_at`] of the fitted values; for readings in the
//! base frame its base becomes `T^-1 base` (the base frame's error, [`Estimate::frame`]), for
//! tracker readings the registration stays with the tracker (its fragment). A DH table holds the
//! errors exactly: in a modified-DH row `i`, `a`, `alpha` and Hayati's `beta` of joint `i` join
//! `a_{i-1}`, `alpha_{i-1}`, `beta_{i-1}`, `theta` and `d` join `theta_offset` and `d_i`; in a
//! standard-DH table `a`, `alpha` and `beta` of joint `i` join row `i - 1` (joint 1's the base
//! transform) and `theta`, `d` row `i` (module docs of [`super::error_model`]). A lateral error
//! `b` has no place in a DH table: a calibration that fitted one writes a URDF only. In a URDF,
//! joint `i`'s origin becomes `post_{i-1} pre_i E_i Rot(w_i, offset_i + theta_i)`, the base folded
//! into the first and the flange into a fixed joint to the `flange` link.

use super::error_model::{ErrorModel, Estimate, MeasuredIn};
use super::gravity::Term;
use nalgebra::{Isometry3, UnitQuaternion, Vector3, Vector6};
use std::fmt::Write;
use stiffid_core::robot::dh::{self, Convention};
use stiffid_core::robot::urdf::UrdfSource;
use stiffid_core::robot::{urdf_write, Bodies};
use stiffid_core::{Error, Result, Robot};

use stiffid_core::robot::CALIBRATED;

/// The calibrated robot: the chain with the fitted errors, the base corrected for base-frame
/// readings.
///
/// # Errors
/// Those of [`ErrorModel::robot_at`] and [`Robot::with_base`].
pub fn calibrated(model: &ErrorModel, estimate: &Estimate) -> Result<Robot> {
    let robot = model.robot_at(&estimate.values)?;
    let robot = match model.external_at(&estimate.values)? {
        Some(axes) => robot.with_external(Some(axes)),
        None => robot,
    };
    match model.measured_in() {
        MeasuredIn::Tracker => Ok(robot),
        MeasuredIn::Base => {
            let base = estimate.frame.inverse() * robot.base();
            robot.with_base(base)
        }
    }
}

/// The share of the robot's size ([`Robot::size`]) by which a written file's flange may miss the
/// calibrated robot's when read back (m per m), and the angle (rad).
const READ_BACK: f64 = 1e-9;

/// The share of the robot's size below which a length counts as zero when a chain is read as a
/// DH table.
const DH_TOLERANCE: f64 = 1e-12;

/// The notation of the nominal robot's table: modified DH when every joint turns about z and its
/// `post` only slides along z, else standard DH (a URDF robot, too).
fn convention(robot: &Robot, tolerance: f64) -> Convention {
    let modified = robot.joints().iter().all(|j| {
        let t = j.post.translation.vector;
        j.axis == Vector3::z_axis()
            && j.post.rotation.angle() < DH_TOLERANCE
            && t.xy().norm() < tolerance
    });
    match modified {
        true => Convention::ModifiedDh,
        false => Convention::StandardDh,
    }
}

/// The robot of a DH `table` with `robot`'s name, axis map, limits and bodies.
fn table_robot(robot: &Robot, table: &dh::Table) -> Result<Robot> {
    let joints =
        std::array::from_fn(|i| dh::hayati_joint(table.convention, &table.rows[i], table.betas[i]));
    let maps = robot.error_maps().cloned().unwrap_or_default();
    Ok(
        Robot::new(robot.name(), robot.source(), joints, *robot.limits())?
            .with_axis_map(robot.axis_map().clone())?
            .with_base(table.base)?
            .with_flange(table.flange)?
            .with_error_maps(maps),
    )
}

/// The `error_map` line of a joint's map (deg, shortest round-trip, with the range it was fitted
/// over), or nothing without one.
fn error_map_line(map: &stiffid_core::robot::ErrorMap) -> String {
    if map.is_empty() {
        return String::new();
    }
    let deg = |v: &[f64]| {
        let parts: Vec<String> = v.iter().map(|x| format!("{:?}", x.to_degrees())).collect();
        parts.join(", ")
    };
    let backlash = match map.backlash() {
        0.0 => String::new(),
        b => format!(", half_backlash_deg = {:?}", b.to_degrees()),
    };
    let range = match map.range() {
        Some((lo, hi)) => format!(
            ", range_deg = [{:?}, {:?}]",
            lo.to_degrees(),
            hi.to_degrees()
        ),
        None => String::new(),
    };
    format!(
        "error_map = {{ cos_deg = [{}], sin_deg = [{}]{backlash}{range} }}\n",
        deg(map.cos()),
        deg(map.sin())
    )
}

/// What a URDF of the calibrated robot leaves out, in words: its joint error maps and half
/// backlashes (a URDF holds none); `None` when it has none.
pub fn urdf_leaves_out(model: &ErrorModel, estimate: &Estimate) -> Option<String> {
    let robot = model.robot_at(&estimate.values).ok()?;
    if let Some(axes) = robot.external() {
        let names: Vec<&str> = axes.axes().iter().map(|a| a.name.as_str()).collect();
        return Some(format!(
            "the URDF leaves out the calibrated external axes ({}: their directions, error motions and lines): use the robot file",
            names.join(", ")
        ));
    }
    let maps = robot.error_maps()?;
    let joints: Vec<usize> = (0..6).filter(|&i| !maps[i].is_empty()).collect();
    let backlash = match maps.iter().any(|m| m.backlash() != 0.0) {
        true => " and their half backlashes",
        false => "",
    };
    Some(format!(
        "the URDF leaves out the error maps{backlash} of {} (a URDF holds no joint error map): a robot read from it misses them; use the robot file",
        stiffid_core::common::warning::joint_list(joints)
    ))
}

/// The calibrated robot as a robot TOML file (module docs): its chain as a DH table in the
/// nominal robot's notation (a URDF robot's in standard DH, [`dh::table`]), Hayati's `beta_deg`
/// where a row needs it, the axis map, joint limits, axis speeds (when any axis has one: `inf` for an axis without), base, flange, capsule radii and masses (their
/// centres carried into the table's link frames) of the nominal robot. Numbers are written in
/// full (shortest round-trip) and the file is read back: its flange is the calibrated robot's
/// within 1e-9 of the robot's size at three postures.
///
/// # Errors
/// [`Error::InvalidField`] (`robot`) when a joint's transform has no DH row (axes at 90 degrees
/// about y after the common normal) or the file read back misses the calibrated robot.
pub fn robot_toml(model: &ErrorModel, estimate: &Estimate) -> Result<String> {
    let nominal = model.robot();
    let (robot, convention, table, written) = tabled(model, estimate)?;
    let mut t = String::new();
    let name = format!(
        "{}{CALIBRATED}",
        nominal.name().trim_end_matches(CALIBRATED)
    );
    let _ = writeln!(t, "name = {}", quoted(&name));
    let _ = writeln!(t, "source = {}", quoted(nominal.source()));
    let _ = writeln!(
        t,
        "convention = \"{}\"",
        match convention {
            Convention::ModifiedDh => "modified-dh",
            Convention::StandardDh => "standard-dh",
        }
    );
    // Every axis's speed when one has a limit: `inf` for one without.
    if nominal.max_speeds().iter().any(|v| v.is_finite()) {
        let deg: Vec<String> = (nominal.max_speeds().iter())
            .map(|v| format!("{:?}", v.to_degrees()))
            .collect();
        let _ = writeln!(t, "max_speed_deg_s = [{}]", deg.join(", "));
    }
    let limits = nominal.limits();
    // A link's centre moves into the table's frame of the same link (both turn with it).
    let (at, table_at) = (
        robot.frames(&Vector6::zeros()),
        written.frames(&Vector6::zeros()),
    );
    for (i, r) in table.rows.iter().enumerate() {
        let _ = writeln!(t, "\n[[joint]]");
        let _ = writeln!(t, "a_mm = {:?}", r.a * 1e3);
        let _ = writeln!(t, "alpha_deg = {:?}", r.alpha.to_degrees());
        if table.betas[i] != 0.0 {
            let _ = writeln!(t, "beta_deg = {:?}", table.betas[i].to_degrees());
        }
        let _ = writeln!(t, "d_mm = {:?}", r.d * 1e3);
        let _ = writeln!(t, "theta_offset_deg = {:?}", r.theta_offset.to_degrees());
        let _ = writeln!(t, "lower_deg = {:?}", limit(limits.lower[i]));
        let _ = writeln!(t, "upper_deg = {:?}", limit(limits.upper[i]));
        if let Some(maps) = robot.error_maps() {
            t += &error_map_line(&maps[i]);
        }
        if let Some(m) = robot.masses() {
            let moved = m[i].moved(&(table_at.joints[i].inverse() * at.joints[i]));
            let _ = writeln!(t, "mass_kg = {:?}", m[i].mass);
            let _ = writeln!(t, "com_mm = {}", list(&(moved.centre * 1e3)));
            if moved.inertia != nalgebra::Matrix3::zeros() {
                let six = stiffid_core::robot::dynamics::body::components(&moved.inertia);
                let six: Vec<String> = six.iter().map(|v| format!("{v:?}")).collect();
                let _ = writeln!(t, "inertia_kg_m2 = [{}]", six.join(", "));
            }
        }
    }
    let map = nominal.axis_map();
    let _ = writeln!(t, "\n[axis_map]\nmatrix = [");
    for r in 0..6 {
        let row: Vec<String> = (0..6)
            .map(|c| format!("{:?}", map.matrix[(r, c)]))
            .collect();
        let _ = writeln!(t, "  [{}],", row.join(", "));
    }
    let offsets: Vec<String> = map
        .offset
        .iter()
        .map(|v| format!("{:?}", v.to_degrees()))
        .collect();
    let _ = writeln!(t, "]\noffset_deg = [{}]", offsets.join(", "));
    let _ = write!(t, "\n[base]\n{}", transform(&table.base));
    let _ = write!(t, "\n[flange]\n{}", transform(&table.flange));
    if *robot.controller_world() != Isometry3::identity() {
        let world = transform(robot.controller_world());
        let _ = write!(t, "\n[controller_world]\n{world}");
    }
    if let Bodies::Capsules(r) = nominal.bodies() {
        let radii: Vec<String> = r.iter().map(|v| format!("{:?}", v * 1e3)).collect();
        let _ = writeln!(
            t,
            "\n[robot_geometry]\nlink_radius_mm = [{}]",
            radii.join(", ")
        );
    }
    if let Some(axes) = robot.external() {
        t += &stiffid_core::robot::external::file::toml(axes);
    }
    let back = stiffid_core::robot::file::parse(&t, "the calibrated robot file")?;
    read_back(&robot, &back).map_err(|e| not_dh(&e))?;
    Ok(t)
}

/// The calibrated robot, the notation of its table, the DH table and the robot of the table.
fn tabled(
    model: &ErrorModel,
    estimate: &Estimate,
) -> Result<(Robot, Convention, dh::Table, Robot)> {
    let robot = calibrated(model, estimate)?;
    let tolerance = DH_TOLERANCE * robot.size();
    let convention = convention(model.robot(), tolerance);
    let Some(table) = dh::table(&robot, convention, tolerance) else {
        return Err(not_dh(
            "a joint's transform has no DH row (consecutive axes at 90 degrees about y): write a URDF instead",
        ));
    };
    let written = table_robot(&robot, &table)?;
    Ok((robot, convention, table, written))
}

/// The calibrated robot file's whole text: the robot ([`robot_toml`]), then `held_out` (its
/// `[held_out]` table as the job writes it), the mount it was calibrated on (`[mount]`: `mount`,
/// the calibration setup's `[robot_base]`, the identity without one, which its `[base]` holds),
/// the part's frame a calibration located from the reflectors on the positioner's table
/// (`[part]`: `part`, cell frame with every external axis at 0, m) and the sag under its own
/// weight `own` with the gravity terms moved into the file's link frames (`[gravity]`).
///
/// # Errors
/// Those of [`robot_toml`] and of the gravity terms' move into the table's frames.
pub fn calibrated_file(
    (model, estimate): (&ErrorModel, &Estimate),
    held_out: &str,
    mount: &Isometry3<f64>,
    (own, part): (
        Option<&stiffid_core::model::OwnWeight>,
        Option<&Isometry3<f64>>,
    ),
) -> Result<String> {
    let text = robot_toml(model, estimate)?;
    let sag = (own.map(|w| own_weight_in_table(model, estimate, w))).transpose()?;
    let sag = sag.map_or(String::new(), |w| {
        stiffid_core::robot::weight_file::toml(&w)
    });
    let part = part.map_or(String::new(), part_table);
    Ok(text + held_out + &mount_table(mount) + &part + &sag)
}

/// `own`, the gravity terms of `model` at `estimate`, in the link frames of the robot file's DH
/// table ([`robot_toml`]), as the file carries them: a lumped term's first moment, fixed in its
/// link's frame, moves with the frame as the masses' centres do, `c m s' = R (c m s) + t (c m)`
/// for each spring and link (`(R, t)` from the link's frame to the table's); compliances stay.
///
/// # Errors
/// Those of [`robot_toml`]'s table.
fn own_weight_in_table(
    model: &ErrorModel,
    estimate: &Estimate,
    own: &stiffid_core::model::OwnWeight,
) -> Result<stiffid_core::model::OwnWeight> {
    let (robot, _, _, written) = tabled(model, estimate)?;
    let (at, table_at) = (
        robot.frames(&Vector6::zeros()),
        written.frames(&Vector6::zeros()),
    );
    let terms = model.gravity().terms();
    let mut moved = own.clone();
    for (i, t) in terms.iter().enumerate() {
        let Term::Lumped {
            joint,
            link,
            moment: 0,
        } = *t
        else {
            continue;
        };
        let at_moment = |k: usize| {
            let want = Term::Lumped {
                joint,
                link,
                moment: k,
            };
            terms.iter().position(|t| *t == want)
        };
        let (Some(x), Some(y), Some(z)) = (at_moment(1), at_moment(2), at_moment(3)) else {
            continue;
        };
        let to = table_at.joints[link].inverse() * at.joints[link];
        let first = Vector3::new(own.terms[x].1, own.terms[y].1, own.terms[z].1);
        let first = to.rotation * first + to.translation.vector * own.terms[i].1;
        (moved.terms[x].1, moved.terms[y].1, moved.terms[z].1) = (first.x, first.y, first.z);
    }
    Ok(moved)
}

/// Whether `back`, a written file read back, has `robot`'s flange at the same axis angles
/// within [`READ_BACK`] of the robot's size (m) and [`READ_BACK`] rad, at three postures, and
/// its controller's world.
fn read_back(robot: &Robot, back: &Robot) -> std::result::Result<(), String> {
    let q = [
        Vector6::zeros(),
        Vector6::new(0.3, -0.4, 0.5, -0.6, 0.7, -0.8),
        Vector6::new(-1.1, 0.9, -0.7, 1.3, -0.5, 2.1),
    ];
    let (mut distance, mut angle) = (0.0_f64, 0.0_f64);
    let flanges = q
        .iter()
        .map(|q| (robot.frames(q).flange, back.frames(q).flange));
    let worlds = (*robot.controller_world(), *back.controller_world());
    for (a, b) in flanges.chain([worlds]) {
        distance = distance.max((a.translation.vector - b.translation.vector).norm());
        angle = angle.max(stiffid_core::robot::file::angle_between(
            &a.rotation,
            &b.rotation,
        ));
    }
    let tolerance = READ_BACK * robot.size();
    match distance <= tolerance && angle <= READ_BACK {
        true => Ok(()),
        false => Err(format!(
            "read back, its flange or controller world misses the calibrated robot's by {:.3e} mm and {:.3e} deg (at most {:.3e} mm, {:.3e} deg)",
            distance * 1e3,
            angle.to_degrees(),
            tolerance * 1e3,
            READ_BACK.to_degrees()
        )),
    }
}

/// The calibrated robot as a URDF (module docs), with the same kinematics, joint limits and axis
/// angles as the robot file. A robot read from a URDF gets its own document back with the
/// origins of its six chain joints corrected (`origin_i N_i^-1 C_i`, `N_i` and `C_i` the nominal
/// and calibrated transforms from the previous joint's frame to joint `i`'s, a base correction
/// folded into the first): links, meshes, inertials, mimic joints, fixed joints and comments
/// kept. Any other robot is written as links `base_link`, `link1`..`link6`, `flange`, revolute
/// joints `joint1`..`joint6` with the corrected origins, the axis map folded in (its constant
/// into the origins, a negative sign into the axis: the URDF's joint positions are the axis
/// angles), the axis limits as joint limits (an unbounded axis a continuous joint) and the
/// links' masses, centres and inertia tensors when the nominal robot has them. Either is read
/// back: its flange is the calibrated robot's within 1e-9 of the robot's size at three
/// postures. It leaves out the joint error maps ([`urdf_leaves_out`]): it is the calibrated
/// chain without them.
///
/// # Errors
/// Those of [`calibrated`]; [`Error::InvalidField`] (`robot`) when the axis map couples axes or
/// scales them (a URDF joint turns by its own position: the robot file carries the map), when
/// the robot was calibrated on a mount `mount` (the calibration setup's `[robot_base]`; not the
/// identity) — a URDF has no place to record it apart from the robot: a robot read from a URDF
/// would get its own document back at its foot, a generated one would carry the mount in its
/// first joint but not in the controller's world (its `base` link), and a setup reading a
/// calibrated robot does not mount it again; the robot file records the mount —, when the
/// nominal URDF's text cannot carry the correction (a chain joint not found in it) or the
/// document read back misses the calibrated robot.
pub fn urdf(model: &ErrorModel, estimate: &Estimate, mount: &Isometry3<f64>) -> Result<String> {
    if *mount != Isometry3::identity() {
        return Err(not_urdf(&format!("it was calibrated on a mount ({}, the setup's [robot_base]), which a URDF cannot record apart from the robot, and a setup reading the calibrated robot does not mount it again: use the robot file (--out), which records the mount", mount_words(mount))));
    }
    let robot = calibrated(model, estimate)?.with_error_maps(Default::default());
    if let Some(source) = model.robot().urdf_source() {
        return edited_urdf(model.robot(), &robot, source);
    }
    let signs = signs(robot.axis_map()).map_err(|e| not_urdf(&e))?;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "<?xml version=\"1.0\"?>\n<robot name={}>",
        xml_quoted(&format!(
            "{}{CALIBRATED}",
            robot.name().trim_end_matches(CALIBRATED)
        ))
    );
    let mut links = vec!["base_link".to_string()];
    links.extend((1..=6).map(|i| format!("link{i}")));
    links.push("flange".into());
    for (i, l) in links.iter().enumerate() {
        match (i, robot.masses()) {
            (1..=6, Some(m)) => {
                // The link frame of the URDF is the joint frame before `post`.
                let m = m[i - 1].moved(&robot.joints()[i - 1].post);
                let (c, [xx, yy, zz, xy, xz, yz]) = (
                    m.centre,
                    stiffid_core::robot::dynamics::body::components(&m.inertia),
                );
                let _ = writeln!(
                    t,
                    "  <link name=\"{l}\"><inertial><origin xyz=\"{:?} {:?} {:?}\"/><mass value=\"{:?}\"/><inertia ixx=\"{xx:?}\" ixy=\"{xy:?}\" ixz=\"{xz:?}\" iyy=\"{yy:?}\" iyz=\"{yz:?}\" izz=\"{zz:?}\"/></inertial></link>",
                    c.x, c.y, c.z, m.mass
                );
            }
            _ => {
                let _ = writeln!(t, "  <link name=\"{l}\"/>");
            }
        }
    }
    let mut before = *robot.base();
    let limits = robot.limits();
    for (i, j) in robot.joints().iter().enumerate() {
        // Rot(w, s q + c + offset) = Rot(w, c + offset) Rot(s w, q).
        let origin = before
            * j.pre
            * UnitQuaternion::from_axis_angle(&j.axis, j.offset + robot.axis_map().offset[i]);
        before = j.post;
        let axis = j.axis.into_inner() * signs[i];
        let (lo, hi) = (limits.lower[i], limits.upper[i]);
        let bounded = lo.is_finite() || hi.is_finite();
        let _ = writeln!(
            t,
            "  <joint name=\"joint{}\" type=\"{}\">\n    <parent link=\"{}\"/><child link=\"{}\"/>\n    {}\n    <axis xyz=\"{:?} {:?} {:?}\"/>",
            i + 1,
            if bounded { "revolute" } else { "continuous" },
            links[i],
            links[i + 1],
            urdf_write::origin_xml(&origin),
            axis.x,
            axis.y,
            axis.z
        );
        if bounded {
            let end = stiffid_core::common::limits::ANGLE_RAD.max;
            let _ = writeln!(
                t,
                "    <limit lower=\"{:?}\" upper=\"{:?}\" effort=\"0\" velocity=\"0\"/>",
                lo.max(-end),
                hi.min(end)
            );
        }
        let _ = writeln!(t, "  </joint>");
    }
    let _ = writeln!(
        t,
        "  <joint name=\"flange\" type=\"fixed\">\n    <parent link=\"link6\"/><child link=\"flange\"/>\n    {}\n  </joint>",
        urdf_write::origin_xml(&(before * robot.flange()))
    );
    if *robot.controller_world() != Isometry3::identity() {
        // ROS-Industrial's `base` link: the controller's world.
        let _ = writeln!(
            t,
            "  <link name=\"base\"/>\n  <joint name=\"base_link-base\" type=\"fixed\">\n    <parent link=\"base_link\"/><child link=\"base\"/>\n    {}\n  </joint>",
            urdf_write::origin_xml(robot.controller_world())
        );
    }
    let _ = writeln!(t, "</robot>");
    let back = stiffid_core::robot::urdf::parse(&t, "the calibrated URDF", Some("flange"))?;
    read_back(&robot, &back).map_err(|e| not_urdf(&e))?;
    Ok(t)
}

/// The sign of each axis in `map` when it is diagonal with entries +-1 (each kinematic angle one
/// axis angle, mirrored or not), or why a URDF cannot carry it.
fn signs(map: &stiffid_core::robot::AxisMap) -> std::result::Result<[f64; 6], String> {
    let m = &map.matrix;
    for r in 0..6 {
        let read: Vec<String> = (0..6)
            .filter(|&c| m[(r, c)] != 0.0)
            .map(|c| format!("q{}", c + 1))
            .collect();
        if read.len() != 1 || m[(r, r)].abs() != 1.0 {
            return Err(format!(
                "its axis map makes joint {}'s angle of {} (axis_map.matrix row {}), and a URDF joint turns by its own position alone: use the robot file (--out), which carries the map",
                r + 1,
                match read.is_empty() {
                    true => "no axis".to_string(),
                    false => format!("{} times {}", m[(r, r)], read.join(" and ")),
                },
                r + 1
            ));
        }
    }
    Ok(std::array::from_fn(|i| m[(i, i)]))
}

/// The nominal URDF `source` of `nominal` with the origins of `calibrated` (the function docs of
/// [`urdf`]), checked by reading it back.
fn edited_urdf(nominal: &Robot, calibrated: &Robot, source: &UrdfSource) -> Result<String> {
    let invalid = |message: String| Error::InvalidField {
        field: "robot".into(),
        message: format!("the calibrated robot cannot be written as a URDF: {message}"),
    };
    // From the previous joint's frame to joint `i`'s at `theta = 0` (the axis map applies to
    // both robots alike and stays out).
    let step = |r: &Robot, i: usize| {
        let before = match i {
            0 => *r.base(),
            _ => r.joints()[i - 1].post,
        };
        let j = &r.joints()[i];
        before * j.pre * UnitQuaternion::from_axis_angle(&j.axis, j.offset)
    };
    let origins: [Isometry3<f64>; 6] = std::array::from_fn(|i| {
        source.origins[i] * step(nominal, i).inverse() * step(calibrated, i)
    });
    let name = match calibrated.name().ends_with(CALIBRATED) {
        true => calibrated.name().to_string(),
        false => format!("{}{CALIBRATED}", calibrated.name()),
    };
    let text = urdf_write::with_origins(source, &name, &origins).map_err(invalid)?;
    let back = stiffid_core::robot::urdf::parse(&text, "the calibrated URDF", Some(&source.tip))?
        .with_base(*nominal.base())?
        .with_axis_map(nominal.axis_map().clone())?;
    read_back(calibrated, &back).map_err(invalid)?;
    Ok(text)
}

/// The robot file's `[mount]` table: the mount `mount` (the calibration setup's `[robot_base]`,
/// the identity without one) a robot was calibrated on, which its `[base]` holds
/// ([`stiffid_core::Robot::mount`]).
fn mount_table(mount: &Isometry3<f64>) -> String {
    format!("\n[mount]\n{}", transform(mount))
}

/// The robot file's `[part]` table: the part's frame `part` a calibration located from the
/// reflectors on the positioner's table (cell frame with every external axis at 0, m;
/// [`stiffid_core::Robot::part`]).
fn part_table(part: &Isometry3<f64>) -> String {
    format!("\n[part]\n{}", transform(part))
}

fn transform(t: &Isometry3<f64>) -> String {
    let [r, p, y] = stiffid_core::robot::file::rpy(&t.rotation);
    format!(
        "xyz_mm = {}\nrpy_deg = [{:?}, {:?}, {:?}]\n",
        list(&(t.translation.vector * 1e3)),
        r.to_degrees(),
        p.to_degrees(),
        y.to_degrees()
    )
}

/// A mount as a setup writes it, short numbers: `xyz_mm = [..], rpy_deg = [..]`.
fn mount_words(t: &Isometry3<f64>) -> String {
    let short = |v: f64| stiffid_core::common::words::number(v + 0.0);
    let p = t.translation.vector * 1e3;
    let [r, pi, y] = stiffid_core::robot::file::rpy(&t.rotation).map(f64::to_degrees);
    format!(
        "xyz_mm = [{}, {}, {}], rpy_deg = [{}, {}, {}]",
        short(p.x),
        short(p.y),
        short(p.z),
        short(r),
        short(pi),
        short(y)
    )
}

fn list(v: &Vector3<f64>) -> String {
    format!("[{:?}, {:?}, {:?}]", v.x, v.y, v.z)
}

/// A joint limit (rad) in degrees; an unbounded end as the file's largest angle.
fn limit(v: f64) -> f64 {
    match v.is_finite() {
        true => v.to_degrees(),
        false => v.signum() * stiffid_core::common::limits::ANGLE_DEG.max,
    }
}

fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

fn xml_quoted(s: &str) -> String {
    let escaped = s
        .replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;");
    format!("\"{escaped}\"")
}

fn not_urdf(message: &str) -> Error {
    Error::InvalidField {
        field: "robot".into(),
        message: format!("the calibrated robot cannot be written as a URDF: {message}"),
    }
}

fn not_dh(message: &str) -> Error {
    Error::InvalidField {
        field: "robot".into(),
        message: format!("the calibrated robot cannot be written as a robot TOML file: {message}"),
    }
}
