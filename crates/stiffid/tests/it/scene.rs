//! The 3D scene against the model: every joint position of every posture equals the kinematics
//! job's; each link's frame carries its shapes where the cell's checks put them; the compliance
//! ellipsoid's axes are the eigen-decomposition of `J K^-1 J^T` worked out here; the arrows are
//! the readings given; the `.glb` reads back with a glTF parser (its validation) with the nodes,
//! names and transforms of the scene; the page fetches nothing.

use super::bodies::mesh_setup;
use nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3, Vector6};
use stiffid::app::document::scene::{self, glb, page, Extras, PathPoint, Scene};
use stiffid::app::measurements::Data;
use stiffid::app::{identify, kinematics};
use stiffid::internal::robot::kinematics::Coordinates;
use stiffid::Setup;

fn tracker_setup() -> Setup {
    let text = stiffid::internal::setup::builtin_text("zhang2021-comau-nj165").unwrap().to_string()
        + "[cell]\nfloor_z_mm = 0.0\n[[cell.obstacle]]\nname = \"table\"\nmin_mm = [1200, -400, 0]\nmax_mm = [1800, 400, 750]\n[tracker]\nposition_mm = [3000.0, -2000.0, 1500.0]\n";
    stiffid::internal::setup::parse(&text, "cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap()
}

fn vector(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

fn with_nominal(setup: &Setup, postures: &[Vector6<f64>]) -> Scene {
    let h = setup.model_nominal_compliance().unwrap();
    let extras = Extras {
        compliance: Some(&h),
        rope: true,
        ..Extras::default()
    };
    scene::scene(setup, postures, &extras).unwrap()
}

#[test]
fn joint_positions_equal_the_kinematics_job_and_link_frames_carry_the_chain() {
    for setup in [tracker_setup(), mesh_setup()] {
        let postures = stiffid::internal::design::random_group(&setup.without_cell(), 6, 11);
        let s = with_nominal(&setup, &postures);
        assert_eq!(s.postures.len(), 6);
        for (p, q) in s.postures.iter().zip(&postures) {
            let report = kinematics::run(&kinematics::Request {
                robot: setup.robot(),
                q: *q,
                point: setup.tool().tcp,
                characteristic_length: Some(1.2),
                coordinates: Coordinates::Axis,
                stiffness: None,
                external: Vec::new(),
                workpiece: None,
            })
            .unwrap();
            let doc = report.document();
            for j in 0..6 {
                let got = vector(p.joint_positions_m[j]) * 1e3;
                let want = vector(doc.joint_positions_mm[j]);
                assert!((got - want).norm() < 1e-9, "joint {j}: {got} vs {want}");
                // Link j + 1 turns with joint j + 1: its frame is that joint's.
                let f = &p.link_frames[j + 1];
                assert!((vector(f.translation_m) * 1e3 - want).norm() < 1e-9);
            }
            let tcp = vector(p.tcp_m) * 1e3;
            assert!((tcp - vector(doc.point_position_mm)).norm() < 1e-9);
            // q as given, in degrees.
            for a in 0..6 {
                assert!((p.q_deg[a] - q[a].to_degrees()).abs() < 1e-12);
            }
        }
    }
}

/// The posed shapes of the scene (link frame times the link's vertices) lie where the cell's
/// bodies are: each vertex within its body's bounding sphere.
#[test]
fn posed_geometry_lies_in_the_cell_bodies_bounds() {
    let setup = mesh_setup();
    let q = stiffid::internal::design::random_group(&setup.without_cell(), 1, 5)[0];
    let s = with_nominal(&setup, &[q]);
    let frames = setup.robot().frames(&q);
    let bodies = stiffid::internal::cell::bodies(setup.arm(), &frames);
    let names: Vec<&str> = s.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "base_link",
            "link_1",
            "link_2",
            "link_3",
            "link_4",
            "link_5",
            "link_6",
            "tool"
        ]
    );
    assert_eq!(
        s.links[1].meshes,
        ["package://mesh_robot/meshes/link_1.stl"]
    );
    assert!(s.notes.iter().any(|n| n.contains("convex hulls")));
    for (k, link) in s.links.iter().enumerate() {
        let f = &s.postures[0].link_frames[k];
        let [x, y, z, w] = f.rotation_xyzw;
        let pose = nalgebra::Isometry3::from_parts(
            vector(f.translation_m).into(),
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)),
        );
        let own: Vec<_> = bodies
            .iter()
            .filter(|b| b.part().to_string() == link.part)
            .collect();
        assert!(!own.is_empty(), "{}", link.part);
        for g in &link.geometry {
            assert!(!g.triangles.is_empty());
            for p in &g.positions_m {
                let at = pose * Point3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
                let inside = own.iter().any(|b| {
                    let (c, r) = b.bound();
                    (at.coords - c).norm() <= r + 1e-5
                });
                assert!(inside, "{} vertex {at} outside its bodies", link.name);
            }
        }
    }
}

#[test]
fn ellipsoid_axes_are_the_eigen_decomposition_of_the_translational_compliance() {
    let setup = tracker_setup();
    let postures = stiffid::internal::design::random_group(&setup.without_cell(), 4, 3);
    let s = with_nominal(&setup, &postures);
    let k = setup.nominal_stiffness().unwrap();
    assert_eq!(s.ellipsoid_force_n, 500.0);
    for (p, q) in s.postures.iter().zip(&postures) {
        // C_tt = J_v K^-1 J_v^T from the axis Jacobian of the TCP, worked out here.
        let j = setup
            .robot()
            .frames(q)
            .jacobian(&setup.tool().tcp, Coordinates::Axis);
        let jv = j.fixed_rows::<3>(0);
        let mut c = Matrix3::zeros();
        for a in 0..6 {
            c += jv.column(a) * jv.column(a).transpose() / k[a];
        }
        assert_ellipsoid(&p.ellipsoid.unwrap(), &c, 500.0);
        assert_eq!(p.ellipsoid.unwrap().centre_m, p.tcp_m);
    }
}

/// `e` is the ellipsoid of the translational compliance `c` (m/N) under `force` (N): unit
/// eigenvectors with rising eigenvalues that rebuild `c`, semi-axes `force c_i`.
fn assert_ellipsoid(e: &scene::Ellipsoid, c: &Matrix3<f64>, force: f64) {
    let mut rebuilt = Matrix3::zeros();
    for i in 0..3 {
        let v = vector(e.axes[i]);
        assert!((v.norm() - 1.0).abs() < 1e-12);
        // An eigenvector: C v = c v.
        assert!((c * v - v * e.compliance_m_per_n[i]).norm() < 1e-9 * c.norm());
        rebuilt += v * v.transpose() * e.compliance_m_per_n[i];
        assert!((e.semi_axes_m[i] - force * e.compliance_m_per_n[i]).abs() < 1e-15);
    }
    assert!((rebuilt - c).norm() < 1e-9 * c.norm());
    assert!(e.compliance_m_per_n[0] <= e.compliance_m_per_n[1]);
    assert!(e.compliance_m_per_n[1] <= e.compliance_m_per_n[2]);
}

/// The identification's scene: the FANUC load tests' postures (joint positions as the
/// kinematics give them), each arrow the document's `measured_mm` and `predicted_mm` of its
/// posture and point, the ellipsoid that of the identified compliance under the setup's load.
#[test]
fn identification_scene_draws_the_documents_displacements_and_compliance() {
    let s = stiffid::internal::setup::builtin("fanuc-r2000ic-165f").unwrap();
    let setup = s.to_builder().with_tcp(s.tool().tcp).build().unwrap();
    let request = identify::Request {
        progress: &(),
        setup_name: "fanuc".into(),
        setup: &setup,
        data: Data::File {
            name: "measurements.csv".into(),
            reader: include_str!("../../../../examples/data/fanuc-r2000ic-165f/measurements.csv")
                .as_bytes(),
        },
        options: identify::Options::default(),
    };
    let report = identify::run(request).unwrap();
    let text = serde_json::to_string(&report.document()).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let postures = report.postures().unwrap();
    let scene = identify::document::scene::scene(&setup, postures, &[], &text).unwrap();
    assert_eq!(scene.postures.len(), postures.len());
    assert!(scene.anchor_m.is_some());
    let residuals = doc["residuals"].as_array().unwrap();
    let mut labels: Vec<&str> = Vec::new();
    let mut drawn = 0;
    for r in residuals {
        let label = r["posture"].as_str().unwrap();
        if !labels.contains(&label) {
            labels.push(label);
        }
        let i = labels.iter().position(|l| *l == label).unwrap();
        let m = r["point"].as_u64().unwrap() as usize - 1;
        let mm = |k: &str| Vector3::from_fn(|c, _| r[k][c].as_f64().unwrap());
        let a = scene.postures[i].arrows[m];
        if vector(a.measured_m.unwrap()) == mm("measured_mm") * 1e-3 {
            assert_eq!(vector(a.predicted_m.unwrap()), mm("predicted_mm") * 1e-3);
            drawn += 1;
        }
        assert!(vector(a.measured_m.unwrap()).norm() >= (mm("measured_mm") * 1e-3).norm());
    }
    assert!(
        drawn >= postures.len(),
        "{drawn} arrows of {}",
        residuals.len()
    );
    let h: Vec<f64> = (0..6)
        .map(|a| doc["compliance_rad_per_nm"][a].as_f64().unwrap())
        .collect();
    for (p, q) in scene.postures.iter().zip(postures) {
        let j = setup
            .robot()
            .frames(q)
            .jacobian(&setup.tool().tcp, setup.model().coordinates());
        let jv = j.fixed_rows::<3>(0);
        let c = (0..6).fold(Matrix3::zeros(), |c, a| {
            c + jv.column(a) * jv.column(a).transpose() * h[a]
        });
        assert_ellipsoid(&p.ellipsoid.unwrap(), &c, setup.load().load);
    }
    // One posture too few, and the model comparison (no residuals): named errors.
    let e = identify::document::scene::scene(&setup, &postures[1..], &[], &text).unwrap_err();
    assert!(e.to_string().contains("postures"), "{e}");
    let e =
        identify::document::scene::scene(&setup, postures, &[], "{\"models\": []}").unwrap_err();
    assert!(e.to_string().contains("residuals"), "{e}");
}

#[test]
fn sights_arrows_and_path_are_the_inputs() {
    let setup = tracker_setup();
    let postures = stiffid::internal::design::random_group(&setup.without_cell(), 3, 8);
    let measured: Vec<Vec<Vector3<f64>>> = (0..3)
        .map(|i| {
            (0..4)
                .map(|m| Vector3::new(1e-3, -2e-4 * m as f64, 3e-4 * i as f64))
                .collect()
        })
        .collect();
    let path: Vec<PathPoint> = (0..50_000)
        .map(|i| PathPoint {
            at_m: [1.0 + i as f64 * 1e-5, 0.0, 0.5],
            error_m: i as f64 * 1e-9,
        })
        .collect();
    let extras = Extras {
        measured: &measured,
        path: &path,
        ..Extras::default()
    };
    let s = scene::scene(&setup, &postures, &extras).unwrap();
    for (p, d) in s.postures.iter().zip(&measured) {
        assert_eq!(p.arrows.len(), 4);
        for (m, a) in p.arrows.iter().enumerate() {
            assert_eq!(a.at_m, p.measuring_points_m[m]);
            assert_eq!(a.measured_m, Some([d[m].x, d[m].y, d[m].z]));
            assert_eq!(a.predicted_m, None);
        }
        assert!(p.ellipsoid.is_none());
        assert_eq!(p.sights.len(), 4);
        for (sight, m) in p.sights.iter().zip(&p.measuring_points_m) {
            assert_eq!(&sight.to_m, m);
            assert!(sight.margin_m.is_finite());
        }
    }
    assert_eq!(s.anchor_m, None);
    assert_eq!(s.tracker_m, Some([3.0, -2.0, 1.5]));
    assert_eq!(s.obstacles[0].max_m, [1.8, 0.4, 0.75]);
    // The documented limit: 20 000 path points.
    assert_eq!(s.path.len(), 20_000);
    assert_eq!(s.path[0], path[0]);
    assert_eq!(s.path.last(), path.last());
    assert!(s.notes.iter().any(|n| n.contains("50000")));
    // Bad input: one list too few, a point missing, a NaN; no posture.
    let mut missing = measured.clone();
    missing[1].pop();
    let mut nan = measured.clone();
    nan[2][3].y = f64::NAN;
    for (bad, says) in [
        (&measured[..2], "one per posture"),
        (&missing[..], "one per posture"),
        (&nan[..], "not finite"),
    ] {
        let short = Extras {
            predicted: bad,
            ..Extras::default()
        };
        let e = scene::scene(&setup, &postures, &short)
            .unwrap_err()
            .to_string();
        assert!(e.contains("predicted") && e.contains(says), "{e}");
    }
    let e = scene::scene(&setup, &[], &Extras::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("postures"), "{e}");
}

#[test]
fn glb_reads_back_with_one_node_per_posture_and_link() {
    let setup = mesh_setup();
    let postures = stiffid::internal::design::random_group(&setup.without_cell(), 3, 2);
    let s = with_nominal(&setup, &postures);
    let bytes = glb::glb(&s);
    // gltf validates the document as it reads it (its `Validate` rules).
    let g = gltf::Gltf::from_slice(&bytes).unwrap();
    let bin = g.blob.as_ref().unwrap();
    let root = g.document.default_scene().unwrap().nodes().next().unwrap();
    assert_eq!(root.name(), Some("stiffid base frame (z up)"));
    let postures_nodes: Vec<_> = root.children().collect();
    assert_eq!(postures_nodes.len(), 3);
    for (i, node) in postures_nodes.iter().enumerate() {
        assert_eq!(node.name(), Some(format!("posture {}", i + 1).as_str()));
        let links: Vec<_> = node.children().collect();
        assert_eq!(links.len(), s.links.len());
        for (k, l) in links.iter().enumerate() {
            assert_eq!(l.name(), Some(s.links[k].name.as_str()));
            let (t, r, _) = l.transform().decomposed();
            let f = &s.postures[i].link_frames[k];
            for (got, want) in t
                .iter()
                .zip(f.translation_m)
                .chain(r.iter().zip(f.rotation_xyzw))
            {
                assert!((f64::from(*got) - want).abs() < 1e-6);
            }
            // The mesh's positions are the scene's, read back from the binary chunk.
            let mesh = l.mesh().unwrap();
            let prims: Vec<_> = mesh.primitives().collect();
            assert_eq!(prims.len(), s.links[k].geometry.len());
            for (prim, geo) in prims.iter().zip(&s.links[k].geometry) {
                let reader = prim.reader(|_| Some(&bin[..]));
                let read: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
                assert_eq!(read, geo.positions_m);
                let idx: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
                let want: Vec<u32> = geo.triangles.iter().flatten().copied().collect();
                assert_eq!(idx, want);
            }
        }
    }
    // A DH robot's links are `link K`.
    let dh = with_nominal(&tracker_setup(), &postures[..1]);
    let g = gltf::Gltf::from_slice(&glb::glb(&dh)).unwrap();
    let names: Vec<_> = g
        .document
        .nodes()
        .filter_map(|n| n.name().map(String::from))
        .collect();
    for k in 1..=6 {
        assert!(names.contains(&format!("link {k}")));
    }
}

#[test]
fn the_page_embeds_everything_and_fetches_nothing() {
    let setup = tracker_setup();
    let postures = stiffid::internal::design::random_group(&setup.without_cell(), 2, 4);
    let html = page::page(&with_nominal(&setup, &postures), "a <scene>");
    assert!(html.contains("<title>a &lt;scene&gt;</title>"));
    // No element loads anything: no src, href or CSS url().
    for needle in [" src=", " href=", "url(", "@import"] {
        assert!(!html.contains(needle), "{needle}");
    }
    // The viewer requests nothing (three.js's loaders, which could, are never called).
    let viewer = &html[html.find("<script type=\"module\">").unwrap()..];
    for needle in ["fetch(", "XMLHttpRequest", "import('http", "WebSocket"] {
        assert!(!viewer.contains(needle), "{needle}");
    }
    // The only absolute URL is the XHTML namespace three.js names (an identifier, not fetched).
    let mut at = 0;
    while let Some(i) = html[at..].find("://") {
        let start = at + i;
        let scheme = &html.as_bytes()[start.saturating_sub(5)..start];
        if scheme.ends_with(b"http") || scheme.ends_with(b"https") {
            assert!(html[start..].starts_with("://www.w3.org/1999/xhtml"));
        }
        at = start + 3;
    }
    // The scene's JSON reads back from the page.
    let open = "id=\"scene-data\">";
    let from = html.find(open).unwrap() + open.len();
    let to = from + html[from..].find("</script>").unwrap();
    let json: serde_json::Value = serde_json::from_str(&html[from..to]).unwrap();
    assert_eq!(json["postures"].as_array().unwrap().len(), 2);
    assert_eq!(json["setup"], setup.name());
}

/// A cell with a track and a tilt-rotate positioner (examples/track/track-cell.toml): each
/// posture at its station, every joint position equal to the kinematics job's with the same
/// external values to 1e-9 mm; the carriage at `C(e) base`, the table at `P(e)`, the rail fixed;
/// their nodes in the `.glb`; values out of the travel refused.
#[test]
fn track_and_positioner_stand_at_each_postures_station() {
    let text = include_str!("../../../../examples/track/track-cell.toml");
    let setup = stiffid::internal::setup::parse(text, "track-cell.toml", |r, _| {
        stiffid::internal::robot::presets::get(r)
    })
    .unwrap();
    let axes = setup.robot().external().unwrap();
    let postures = stiffid::internal::design::random_group(&setup.without_cell(), 3, 6);
    let d = f64::to_radians;
    let stations = vec![
        vec![0.5, d(20.0), d(45.0)],
        vec![3.0, d(-60.0), d(200.0)],
        vec![5.9, 0.0, d(-90.0)],
    ];
    let extras = Extras {
        external: &stations,
        ..Extras::default()
    };
    let s = scene::scene(&setup, &postures, &extras).unwrap();
    let names: Vec<&str> = s.links.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(names[8..], ["track", "carriage", "positioner table"]);
    for ((p, q), e) in s.postures.iter().zip(&postures).zip(&stations) {
        assert_eq!(&p.external, e);
        let report = kinematics::run(&kinematics::Request {
            robot: setup.robot(),
            q: *q,
            point: setup.tool().tcp,
            characteristic_length: Some(1.2),
            coordinates: Coordinates::Axis,
            stiffness: None,
            external: e.clone(),
            workpiece: None,
        })
        .unwrap();
        let doc = report.document();
        for j in 0..6 {
            let got = vector(p.joint_positions_m[j]) * 1e3;
            let want = vector(doc.joint_positions_mm[j]);
            assert!((got - want).norm() < 1e-9, "joint {j}: {got} vs {want}");
        }
        assert!((vector(p.tcp_m) * 1e3 - vector(doc.point_position_mm)).norm() < 1e-9);
        // The robot's base link on the carriage, the carriage at C(e) base, the table at P(e).
        let carriage = axes.carrier_pose(e) * setup.robot().base();
        let table = axes.positioner_pose(e);
        for (k, want) in [(0, carriage), (9, carriage), (10, table)] {
            let f = &p.link_frames[k];
            assert!((vector(f.translation_m) - want.translation.vector).norm() < 1e-12);
            let r = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                f.rotation_xyzw[3],
                f.rotation_xyzw[0],
                f.rotation_xyzw[1],
                f.rotation_xyzw[2],
            ));
            assert!(r.angle_to(&want.rotation) < 1e-12);
        }
        assert_eq!(p.link_frames[8].translation_m, [0.0; 3]);
    }
    // The carriage moves along x by the track's values.
    let x: Vec<f64> = s
        .postures
        .iter()
        .map(|p| p.link_frames[9].translation_m[0])
        .collect();
    assert!((x[1] - x[0] - 2.5).abs() < 1e-12 && (x[2] - x[0] - 5.4).abs() < 1e-12);
    let g = gltf::Gltf::from_slice(&glb::glb(&s)).unwrap();
    let nodes: Vec<_> = g
        .nodes()
        .filter_map(|n| n.name().map(String::from))
        .collect();
    for name in ["track", "carriage", "positioner table"] {
        assert_eq!(nodes.iter().filter(|n| *n == name).count(), 3, "{name}");
    }
    let far = vec![vec![6.5, 0.0, 0.0]; 3];
    let e = scene::scene(
        &setup,
        &postures,
        &Extras {
            external: &far,
            ..Extras::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("external[0]") && e.contains("e1_mm"), "{e}");
    let short = &stations[..2];
    let e = scene::scene(
        &setup,
        &postures,
        &Extras {
            external: short,
            ..Extras::default()
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("one per posture"), "{e}");
}
