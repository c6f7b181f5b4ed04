//! A plausible 6R industrial robot (the proportions of a 150-200 kg, 2.6 m reach machine, with
//! ROS-Industrial's link and joint names and conventions) whose links carry binary STL collision
//! meshes, generated here: a `package://mesh_robot/...` URDF and its meshes as files in memory.
//! Shared by the library's tests and benches (`#[path]`), never copied from a vendor's files.

use std::collections::HashMap;
use std::path::PathBuf;

/// The URDF's path inside a package directory, and the package's name.
pub const URDF: &str = "mesh_robot/urdf/robot.urdf";

/// A convex prism: a regular `sides`-gon of circumradius `radius` about the axis `axis` (0 x,
/// 1 y, 2 z), from `from` to `to` along it, centred at `(c1, c2)` in the other two coordinates
/// (in increasing order), as triangles.
fn prism(
    axis: usize,
    radius: f64,
    from: f64,
    to: f64,
    centre: [f64; 2],
    sides: usize,
) -> Vec<[[f32; 3]; 3]> {
    let (u, v) = match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let point = |k: usize, along: f64| {
        let t = std::f64::consts::TAU * (k % sides) as f64 / sides as f64;
        let mut p = [0f32; 3];
        p[axis] = along as f32;
        p[u] = (centre[0] + radius * t.cos()) as f32;
        p[v] = (centre[1] + radius * t.sin()) as f32;
        p
    };
    let centre_at = |along: f64| {
        let mut p = [0f32; 3];
        p[axis] = along as f32;
        p[u] = centre[0] as f32;
        p[v] = centre[1] as f32;
        p
    };
    let (c0, c1) = (centre_at(from), centre_at(to));
    let mut out = Vec::new();
    for k in 0..sides {
        let (a, b) = (point(k, from), point(k + 1, from));
        let (c, d) = (point(k, to), point(k + 1, to));
        out.extend([[a, b, d], [a, d, c], [c0, b, a], [c1, c, d]]);
    }
    out
}

/// Binary STL of `triangles` (normals left zero, as readers recompute them).
fn stl(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        b.extend([0f32; 3].iter().flat_map(|v| v.to_le_bytes()));
        b.extend(t.iter().flatten().flat_map(|v| v.to_le_bytes()));
        b.extend([0u8; 2]);
    }
    b
}

/// The meshes by link, in the link frames (m): base column, turret, upper arm, elbow housing,
/// forearm, wrist and flange; `sides` the polygon's sides of every prism.
fn meshes(sides: usize) -> Vec<(&'static str, Vec<[[f32; 3]; 3]>)> {
    let mut turret = prism(2, 0.36, 0.15, 0.62, [0.0, 0.0], sides);
    turret.extend(prism(1, 0.26, -0.3, 0.3, [0.32, 0.78], sides));
    vec![
        ("base_link", prism(2, 0.42, 0.0, 0.15, [0.0, 0.0], sides)),
        ("link_1", turret),
        ("link_2", prism(2, 0.17, -0.05, 1.28, [0.0, 0.0], sides)),
        ("link_3", prism(1, 0.24, -0.25, 0.25, [0.0, 0.0], sides)),
        ("link_4", prism(0, 0.14, 0.2, 1.35, [0.0, 0.0], sides)),
        ("link_5", prism(1, 0.11, -0.12, 0.12, [0.0, 0.0], sides)),
        ("link_6", prism(0, 0.08, 0.0, 0.03, [0.0, 0.0], sides)),
    ]
}

/// The URDF: ROS-Industrial's names (`base_link`, `link_1..6`, `joint_1..6`, `flange`, `tool0`),
/// joint 1 about z, 2 and 3 about y, 4 about x, 5 about y, 6 about x; `tool0`'s z axis along the
/// flange's x (ROS-Industrial's convention).
fn urdf() -> String {
    let link = |name: &str| {
        format!(
            "  <link name=\"{name}\"><collision><geometry><mesh filename=\"package://mesh_robot/meshes/{name}.stl\"/></geometry></collision></link>\n"
        )
    };
    let joint = |i: usize, parent: &str, xyz: &str, axis: &str, limits: (f64, f64)| {
        format!(
            "  <joint name=\"joint_{i}\" type=\"revolute\"><parent link=\"{parent}\"/><child link=\"link_{i}\"/><origin xyz=\"{xyz}\"/><axis xyz=\"{axis}\"/><limit lower=\"{}\" upper=\"{}\" effort=\"0\" velocity=\"2\"/></joint>\n",
            limits.0.to_radians(),
            limits.1.to_radians()
        )
    };
    let mut text = String::from("<robot name=\"mesh_robot\">\n");
    for name in [
        "base_link",
        "link_1",
        "link_2",
        "link_3",
        "link_4",
        "link_5",
        "link_6",
    ] {
        text += &link(name);
    }
    text += "  <link name=\"flange\"/>\n  <link name=\"tool0\"/>\n";
    text += &joint(1, "base_link", "0 0 0", "0 0 1", (-170.0, 170.0));
    text += &joint(2, "link_1", "0.32 0 0.78", "0 1 0", (-65.0, 85.0));
    text += &joint(3, "link_2", "0 0 1.28", "0 1 0", (-180.0, 70.0));
    text += &joint(4, "link_3", "0 0 0.2", "1 0 0", (-300.0, 300.0));
    text += &joint(5, "link_4", "1.5 0 0", "0 1 0", (-130.0, 130.0));
    text += &joint(6, "link_5", "0.2 0 0", "1 0 0", (-360.0, 360.0));
    text += "  <joint name=\"joint_6-flange\" type=\"fixed\"><parent link=\"link_6\"/><child link=\"flange\"/></joint>\n";
    text += "  <joint name=\"flange-tool0\" type=\"fixed\"><parent link=\"flange\"/><child link=\"tool0\"/><origin rpy=\"0 1.5707963267948966 0\"/></joint>\n";
    text + "</robot>\n"
}

/// Every file of the package directory: the URDF ([`URDF`]) and one binary STL per link, prisms of
/// `sides` sides (48: 96 hull vertices a link), keyed by their path under the package directory.
pub fn files(sides: usize) -> HashMap<PathBuf, Vec<u8>> {
    let mut out = HashMap::from([(PathBuf::from(URDF), urdf().into_bytes())]);
    for (name, triangles) in meshes(sides) {
        out.insert(
            PathBuf::from(format!("mesh_robot/meshes/{name}.stl")),
            stl(&triangles),
        );
    }
    out
}

/// A setup of the robot in a cell (a floor 0.1 m below its base, 30 mm clearance, a table, a
/// tracker), the paper's tool, load and noise: its TOML text, to be read from the package
/// directory (its `robot` is [`URDF`], its `package_paths` the directory itself).
pub fn setup_toml() -> String {
    format!(
        r#"name = "mesh-robot-cell"
robot = "{URDF}"
package_paths = ["."]
characteristic_length_mm = 1200.0
nominal_stiffness_nm_per_rad = [950000, 3000000, 900000, 250000, 200000, 150000]
[tool]
loading_point_mm = [150.0, 0.0, 200.0]
measuring_points_mm = [[80.0, 80.0, 260.0], [-80.0, 80.0, 260.0], [80.0, -80.0, 260.0], [-80.0, -80.0, 260.0]]
[loading]
load_n = 500.0
anchor_mm = [1500.0, 1500.0, 0.0]
[noise]
reading_sd_mm = 0.0068
level_multiples = [1.0]
[bounds]
lower_deg = [-90.0, -60.0, -150.0, -180.0, -110.0, -180.0]
upper_deg = [90.0, 70.0, 50.0, 180.0, 110.0, 180.0]
[cell]
floor_z_mm = -100.0
clearance_mm = 30.0
[[cell.obstacle]]
name = "table"
min_mm = [1400.0, -1800.0, -100.0]
max_mm = [2400.0, -700.0, 750.0]
[tracker]
position_mm = [3500.0, -1500.0, 1400.0]
"#
    )
}
