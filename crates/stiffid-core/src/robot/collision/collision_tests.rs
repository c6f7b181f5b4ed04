use crate::robot::collision::*;
use crate::Result;
use nalgebra::Vector6;
use nalgebra::{Isometry3, Vector3};
use parry3d_f64::shape::Cuboid;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The signed distance between two posed shapes, m, as the cell's checks measure it
/// ([`crate::cell::body_body`]: parry's GJK apart, EPA inside; never its box-to-box shortcut, which
/// sums the gaps along the axes instead of taking their norm). The part and the bounding sphere
/// play no part in the distance.
fn distance(a: &Shape, pose_a: &Isometry3<f64>, b: &Shape, pose_b: &Isometry3<f64>) -> f64 {
    let solid = |shape: &Shape, pose: &Isometry3<f64>| {
        crate::cell::Body::Solid(crate::cell::Solid {
            part: crate::cell::Part::Base,
            shape: shape.clone(),
            pose: *pose,
            bound: (pose.translation.vector, f64::INFINITY),
        })
    };
    crate::cell::body_body(&solid(a, pose_a), &solid(b, pose_b))
}

/// The 12 triangles of an axis-aligned cube of side `side` centred on the origin.
fn cube(side: f32) -> Vec<[[f32; 3]; 3]> {
    let h = side / 2.0;
    let c = |i: usize| {
        [
            if i & 1 == 0 { -h } else { h },
            if i & 2 == 0 { -h } else { h },
            if i & 4 == 0 { -h } else { h },
        ]
    };
    let faces = [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ];
    faces
        .iter()
        .flat_map(|f| [[c(f[0]), c(f[1]), c(f[2])], [c(f[0]), c(f[2]), c(f[3])]])
        .collect()
}

fn ascii_stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut s = String::from("solid cube\n");
    for t in triangles {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for v in t {
            s += &format!("      vertex {} {} {}\n", v[0], v[1], v[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    (s + "endsolid cube\n").into_bytes()
}

fn binary_stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        b.extend([0f32; 3].iter().flat_map(|v| v.to_le_bytes()));
        b.extend(t.iter().flatten().flat_map(|v| v.to_le_bytes()));
        b.extend([0u8; 2]);
    }
    b
}

const URDF: &str = r#"<robot name="shapes">
  <link name="base_link"><collision><origin xyz="0 0 0.1"/><geometry><box size="0.4 0.4 0.2"/></geometry></collision></link>
  <link name="link_1"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="link_2"><collision><origin xyz="0 0 0.3"/><geometry><cylinder radius="0.05" length="0.6"/></geometry></collision></link>
  <link name="link_3"><collision><geometry><mesh filename="package://testpkg/meshes/cube.stl"/></geometry></collision></link>
  <link name="link_4"><collision><geometry><mesh filename="meshes/cube_bin.stl" scale="2 2 2"/></geometry></collision></link>
  <link name="link_5"/>
  <link name="link_6"/>
  <link name="tool0"><collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision></link>
  <link name="piston"><collision><geometry><sphere radius="0.01"/></geometry></collision></link>
  <joint name="joint_1" type="revolute"><parent link="base_link"/><child link="link_1"/><origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="joint_2" type="revolute"><parent link="link_1"/><child link="link_2"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="joint_3" type="revolute"><parent link="link_2"/><child link="link_3"/><origin xyz="0 0 0.6"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="joint_4" type="revolute"><parent link="link_3"/><child link="link_4"/><origin xyz="0.3 0 0"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="joint_5" type="revolute"><parent link="link_4"/><child link="link_5"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="joint_6" type="revolute"><parent link="link_5"/><child link="link_6"/><axis xyz="1 0 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="flange" type="fixed"><parent link="link_6"/><child link="tool0"/><origin xyz="0.1 0 0"/></joint>
  <joint name="piston_joint" type="revolute"><parent link="link_1"/><child link="piston"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="joint_2" multiplier="-0.25"/></joint>
</robot>"#;

fn files() -> HashMap<PathBuf, Vec<u8>> {
    HashMap::from([
        (
            PathBuf::from("pkgs/testpkg/meshes/cube.stl"),
            ascii_stl(&cube(0.125)),
        ),
        (
            PathBuf::from("robots/meshes/cube_bin.stl"),
            binary_stl(&cube(0.125)),
        ),
    ])
}

fn geometry(package_paths: &[PathBuf]) -> Result<CollisionGeometry> {
    let files = files();
    let read = move |p: &Path| files.get(p).cloned().map(Ok);
    parse(
        URDF,
        "shapes.urdf",
        Path::new("robots"),
        None,
        package_paths,
        &read,
    )
}

/// The posed shape of `link` at posture `q` (rad).
fn posed(g: &CollisionGeometry, link: &str, q: &Vector6<f64>) -> (Shape, Isometry3<f64>) {
    let robot = crate::robot::urdf::parse(URDF, "shapes.urdf", None).unwrap();
    let frames = robot.frames(q);
    let s = g.shapes.iter().find(|s| s.link == link).unwrap();
    let body = match s.body {
        0 => *robot.base(),
        i => frames.joints[i - 1],
    };
    (s.shape.clone(), body * s.origin)
}

fn gap(g: &CollisionGeometry, a: &str, b: &str, q: &Vector6<f64>) -> f64 {
    let ((sa, pa), (sb, pb)) = (posed(g, a, q), posed(g, b, q));
    distance(&sa, &pa, &sb, &pb)
}

#[test]
fn primitives_and_meshes_give_hand_computed_distances() {
    let g = geometry(&[PathBuf::from("pkgs")]).unwrap();
    assert_eq!(g.skipped, ["piston"]);
    let bodies: Vec<(usize, &str)> = g.shapes.iter().map(|s| (s.body, s.link.as_str())).collect();
    assert_eq!(
        bodies,
        [
            (0, "base_link"),
            (1, "link_1"),
            (2, "link_2"),
            (3, "link_3"),
            (4, "link_4"),
            (6, "tool0")
        ]
    );
    let zero = Vector6::zeros();
    let close = |got: f64, want: f64| assert!((got - want).abs() < 1e-9, "{got} vs {want}");
    // Box top at z = 0.2, sphere centre at z = 0.5, radius 0.1.
    close(gap(&g, "base_link", "link_1", &zero), 0.2);
    // The cylinder spans z 0.5..1.1 along z, radius 0.05.
    close(gap(&g, "base_link", "link_2", &zero), 0.3);
    // The ASCII cube (side 0.125, exact in f32) at z = 1.1; the binary one scaled to side 0.25
    // at x = 0.3.
    close(gap(&g, "base_link", "link_3", &zero), 1.1 - 0.0625 - 0.2);
    close(gap(&g, "link_1", "link_3", &zero), 1.1 - 0.0625 - 0.6);
    close(gap(&g, "link_3", "link_4", &zero), 0.3 - 0.125 - 0.0625);
    // tool0 at (0.4, 0, 1.1) through the fixed flange joint.
    let tool0 = posed(&g, "tool0", &zero).1.translation.vector;
    assert!((tool0 - Vector3::new(0.4, 0.0, 1.1)).norm() < 1e-12);
    // Joint 2 at 90 deg lays the cylinder along x at z = 0.5: 0.45 - 0.2 above the box.
    let bent = Vector6::new(0.0, std::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.0, 0.0);
    close(gap(&g, "base_link", "link_2", &bent), 0.25);
    // Overlap is negative: the sphere sits on the cylinder's end, 0.1 deep.
    assert!(gap(&g, "link_1", "link_2", &zero) < -0.05);
}

#[test]
fn package_urls_resolve_in_the_package_paths_or_name_the_package() {
    let e = geometry(&[]).unwrap_err().to_string();
    assert!(
        e.contains(
            "link 'link_3': mesh 'package://testpkg/meshes/cube.stl' is in package 'testpkg'"
        ),
        "{e}"
    );
    let e = geometry(&[PathBuf::from("elsewhere")])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("package 'testpkg' not found in the package paths (no elsewhere/testpkg/meshes/cube.stl)"),
        "{e}"
    );
    let g = geometry(&[PathBuf::from("elsewhere"), PathBuf::from("pkgs")]).unwrap();
    assert_eq!(g.shapes.len(), 6);
    let flat = URDF.replace(
        "cube_bin.stl\" scale=\"2 2 2\"",
        "cube_bin.stl\" scale=\"2 2 0\"",
    );
    let read = |p: &Path| files().get(p).cloned().map(Ok);
    let e = parse(
        &flat,
        "s.urdf",
        Path::new("robots"),
        None,
        &[PathBuf::from("pkgs")],
        &read,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("link 'link_4': collision mesh scale"), "{e}");
}

/// The geometry with `robots/meshes/cube_bin.stl` holding `bytes`.
fn with_binary_mesh(bytes: Vec<u8>) -> Result<CollisionGeometry> {
    let mut files = files();
    files.insert(PathBuf::from("robots/meshes/cube_bin.stl"), bytes);
    let read = move |p: &Path| files.get(p).cloned().map(Ok);
    let pkgs = [PathBuf::from("pkgs")];
    parse(URDF, "s.urdf", Path::new("robots"), None, &pkgs, &read)
}

#[test]
fn a_flat_mesh_is_refused_in_any_plane() {
    // Two triangles of a square in a tilted plane (normal (1, 1, 1)): no volume.
    let (a, b, c, d) = (
        [1.0, -1.0, 0.0],
        [0.0, 1.0, -1.0],
        [-1.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
    );
    let e = with_binary_mesh(binary_stl(&[[a, b, c], [a, c, d]]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("link 'link_4': mesh robots/meshes/cube_bin.stl: its points span no volume (empty, or flat"), "{e}");
    // A thin but solid plate (0.1 mm over 0.125 m) is a body.
    let mut plate = cube(0.125);
    for t in &mut plate {
        for v in t.iter_mut() {
            v[2] *= 0.0008;
        }
    }
    assert_eq!(
        with_binary_mesh(binary_stl(&plate)).unwrap().shapes.len(),
        6
    );
}

#[test]
fn a_binary_header_counting_other_than_the_file_holds_is_refused() {
    let full = binary_stl(&cube(0.125));
    for claimed in [11u32, 13] {
        let mut bytes = full.clone();
        bytes[80..84].copy_from_slice(&claimed.to_le_bytes());
        let e = with_binary_mesh(bytes).unwrap_err().to_string();
        assert!(
            e.contains(&format!(
                "its header says {claimed} triangles ({} bytes), but the file holds 684 bytes",
                84 + 50 * claimed
            )),
            "{e}"
        );
    }
    let e = with_binary_mesh(full[..40].to_vec())
        .unwrap_err()
        .to_string();
    assert!(e.contains("not an STL file (40 bytes"), "{e}");
}

/// parry's box-to-box distance (its cuboid-cuboid closest points) against alternating
/// projections, exact on boxes, in rotated poses of every feature pair (face, edge, vertex).
#[test]
fn box_to_box_distances_equal_alternating_projections() {
    let a = Cuboid::new(Vector3::new(0.2, 0.2, 0.1));
    let b = Cuboid::new(Vector3::new(0.05, 0.3, 0.02));
    // The oracle in plain arrays (the tests' code is not optimised), up to 100 000 projections.
    let clamp = |p: [f64; 3], h: &Vector3<f64>| std::array::from_fn(|i| p[i].clamp(-h[i], h[i]));
    for k in 0..64 {
        let t = f64::from(k);
        let pose = Isometry3::new(
            Vector3::new(
                (t * 0.37).sin() * 1.5,
                (t * 0.71).cos() * 1.2,
                (t * 0.13).sin(),
            ),
            Vector3::new((t * 1.1).sin(), (t * 0.3).cos(), (t * 0.9).sin()),
        );
        let r = pose.rotation.to_rotation_matrix().into_inner();
        let r: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| r[(i, j)]));
        let t: [f64; 3] = pose.translation.vector.into();
        let (mut x, mut y) = ([0.0; 3], t);
        for _ in 0..100_000 {
            x = clamp(y, &a.half_extents);
            // The point x in b's frame, clamped to b, back in a's: r^T (x - t), then r l + t.
            let d: [f64; 3] = std::array::from_fn(|i| x[i] - t[i]);
            let l = clamp(
                std::array::from_fn(|j| (0..3).map(|i| r[i][j] * d[i]).sum()),
                &b.half_extents,
            );
            let next = std::array::from_fn(|i| (0..3).map(|j| r[i][j] * l[j]).sum::<f64>() + t[i]);
            // A fixed point repeats itself: the remaining projections would change nothing.
            if next == y {
                break;
            }
            y = next;
        }
        let gap = (0..3).map(|i| (x[i] - y[i]).powi(2)).sum::<f64>().sqrt();
        let (a_, b_) = (Shape::Cuboid(a), Shape::Cuboid(b));
        let d = distance(&a_, &Isometry3::identity(), &b_, &pose);
        assert!((d - gap).abs() < 1e-9, "{d} vs {gap}");
    }
    // By hand: a cube of side 1 turned 45 deg about z, 2 m along x from another: its edge
    // at 2 - sqrt(1/2) faces the first's face at 0.5.
    let cube = Shape::Cuboid(Cuboid::new(Vector3::repeat(0.5)));
    let turned = Isometry3::new(
        Vector3::x() * 2.0,
        Vector3::z() * std::f64::consts::FRAC_PI_4,
    );
    let d = distance(&cube, &Isometry3::identity(), &cube, &turned);
    assert!((d - (1.5 - 0.5f64.sqrt())).abs() < 1e-12, "{d}");
    // Corner to corner: sqrt(3) along the diagonal.
    let corner = Isometry3::translation(2.0, 2.0, 2.0);
    let d = distance(&cube, &Isometry3::identity(), &cube, &corner);
    assert!((d - 3f64.sqrt()).abs() < 1e-12, "{d}");
}

/// A mesh of exactly [`MAX_MESH_TRIANGLES`] triangles is read (its repeated vertices hulled once:
/// the cube's eight), one more is refused naming the mesh and the way out.
#[test]
fn a_mesh_beyond_the_triangle_limit_is_refused_asking_for_a_decimated_one() {
    let many =
        |n: usize| -> Vec<[[f32; 3]; 3]> { cube(0.125).into_iter().cycle().take(n).collect() };
    let at = with_binary_mesh(binary_stl(&many(MAX_MESH_TRIANGLES))).unwrap();
    let hull = at.shapes.iter().find_map(|s| match &s.shape {
        Shape::Convex(c) if s.link == "link_4" => Some(c.points().len()),
        _ => None,
    });
    assert_eq!(hull, Some(8));
    let e = with_binary_mesh(binary_stl(&many(MAX_MESH_TRIANGLES + 1)))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("mesh robots/meshes/cube_bin.stl: more than 100000 triangles: decimate the collision mesh"),
        "{e}"
    );
}
