//! The 3D scene of a group of postures in the cell: the robot at every posture (each link's
//! frame from the robot's kinematics, its geometry in that frame), the cell's floor and
//! obstacles, the tracker and its lines of sight with their margins, the rope from the loading
//! point to its anchor, the compliance ellipsoid at the tool centre point scaled to a force, the
//! measured and predicted displacements of the measuring points, and a path coloured by its
//! predicted error; with external axes, the track's rail, the carriage at each posture's
//! station and the positioner's table at its angles. What `select --report`,
//! `compensate --report`, `calibrate --report` and `identify --report` draw in 3D, and Python's
//! `stiffid.scene`.
//!
//! Everything in SI: metres, newtons, the unit in every field name (`_m`, `_n`, `_m_per_n`), as
//! glTF and WebGL take them. Written as JSON, as glTF binary ([`glb`]: one node per posture named
//! `posture N` holding one node per link named as the URDF names it) and as a self-contained
//! HTML page ([`page`]).
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links, rustdoc::private_intra_doc_links)]

mod external;
mod geometry;
pub mod glb;
pub mod page;
pub mod stance;

use nalgebra::{DVector, Isometry3, Matrix3, SymmetricEigen, Vector3, Vector6};
use serde::Serialize;
use stiffid_core::cell::{CheckKind, Checker, Thing};
use stiffid_core::observation::cartesian;
use stiffid_core::Setup;

/// Most postures a scene draws.
pub const MAX_POSTURES: usize = 500;

/// Most path points a scene draws (20 000; a longer path is thinned evenly to this many).
pub(crate) const MAX_PATH_POINTS: usize = 20_000;

/// What a scene shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Scene {
    /// The setup's name.
    pub setup: String,
    /// The robot's name.
    pub robot: String,
    /// The robot's links and the tool, with their geometry in their own frames; with external
    /// axes then `track` and `carriage` (a carrier) and `positioner table` (a positioner).
    pub links: Vec<Link>,
    /// Each posture, in the order given.
    pub postures: Vec<Posture>,
    /// The floor's height (base z), m; `null` without a floor.
    pub floor_z_m: Option<f64>,
    /// The cell's obstacles (boxes), base frame; a box the positioner carries where each
    /// posture's external values put it ([`Obstacle::frames`]).
    pub obstacles: Vec<Obstacle>,
    /// The tracker head, base frame, m; `null` without `[tracker]`.
    pub tracker_m: Option<[f64; 3]>,
    /// The rope's anchor (pulley), base frame, m; `null` when the scene has no rope.
    pub anchor_m: Option<[f64; 3]>,
    /// The force the compliance ellipsoids are scaled to, N.
    pub ellipsoid_force_n: f64,
    /// The path over the part, base frame, with its predicted error; empty without a path.
    pub path: Vec<PathPoint>,
    /// What the path's error is, in words; empty without a path.
    pub path_error: String,
    /// What the arrows' two displacements are, in words: `measured_m`'s, `predicted_m`'s.
    pub arrow_names: [String; 2],
    /// What the drawing simplifies, in words (meshes drawn as convex hulls, a thinned path).
    pub notes: Vec<String>,
}

/// A link (or the tool) and its geometry in its own frame.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Link {
    /// Its name: the URDF's link (the root link for the base), else `base`, `link K`; `tool`.
    pub name: String,
    /// The robot part it is: `base`, `link 1`..`link 6`, `tool`.
    pub part: String,
    /// The mesh files of its collision elements as the URDF names them; empty for primitives and
    /// capsules.
    pub meshes: Vec<String>,
    /// Its shapes as triangles in its frame.
    pub geometry: Vec<Geometry>,
}

/// One shape as a triangle mesh.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Geometry {
    /// What it is: `mesh hull` (a mesh's convex hull), `box`, `cylinder`, `sphere`, `capsule`.
    pub kind: String,
    /// Vertex positions in the link's frame, m.
    pub positions_m: Vec<[f32; 3]>,
    /// Triangles: three indices into the positions each.
    pub triangles: Vec<[u32; 3]>,
}

/// A rigid transform: `p_parent = R p + t`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Frame {
    /// The translation t, m.
    pub translation_m: [f64; 3],
    /// The rotation R as a unit quaternion `[x, y, z, w]` (glTF's order).
    pub rotation_xyzw: [f64; 4],
}

/// The robot in one posture.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Posture {
    /// Axis angles, deg.
    pub q_deg: [f64; 6],
    /// The external axes' values (SI: m for a linear axis, rad for a rotary one), the cell's
    /// order; empty without external axes.
    pub external: Vec<f64>,
    /// Each link's frame in the base frame, in the order of [`Scene::links`].
    pub link_frames: Vec<Frame>,
    /// The origin of each joint frame ([`stiffid_core::Frames::joints`]), base frame, m.
    pub joint_positions_m: [[f64; 3]; 6],
    /// The flange's origin, base frame, m.
    pub flange_m: [f64; 3],
    /// The tool centre point, base frame, m.
    pub tcp_m: [f64; 3],
    /// The loading point, base frame, m.
    pub loading_point_m: [f64; 3],
    /// The measuring points, base frame, m.
    pub measuring_points_m: Vec<[f64; 3]>,
    /// The tracker's line of sight to each measuring point; empty without `[tracker]`.
    pub sights: Vec<Sight>,
    /// The compliance ellipsoid at the tool centre point; `null` without a stiffness.
    pub ellipsoid: Option<Ellipsoid>,
    /// The displacement of each measuring point (or point of a campaign), measured and
    /// predicted.
    pub arrows: Vec<Arrow>,
    /// Whether every check of the cell passes; `null` without cell checks.
    pub feasible: Option<bool>,
}

/// The line of sight from the tracker to one measuring point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Sight {
    /// The measuring point, base frame, m (the line starts at [`Scene::tracker_m`]).
    pub to_m: [f64; 3],
    /// Its smallest margin to the bodies, the rope and the obstacles beyond the clearance, m
    /// (negative: blocked).
    pub margin_m: f64,
}

/// The compliance ellipsoid of a tool point: the displacements `C_tt f` of every force `f` of
/// magnitude [`Scene::ellipsoid_force_n`], `C_tt` the translational block of the Cartesian
/// compliance `C_x = J K^-1 J^T` (Salisbury 1980; [`stiffid_core::observation::cartesian`]). With
/// `C_tt = V diag(c) V^T`, its semi-axes are `F c_i` along the eigenvectors `v_i`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Ellipsoid {
    /// Its centre (the tool centre point), base frame, m.
    pub centre_m: [f64; 3],
    /// The eigenvalues c of `C_tt`, rising, m/N.
    pub compliance_m_per_n: [f64; 3],
    /// The unit eigenvectors, one per eigenvalue, base frame.
    pub axes: [[f64; 3]; 3],
    /// The semi-axes `F c_i`, m.
    pub semi_axes_m: [f64; 3],
}

/// The displacement of one point, measured and predicted.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Arrow {
    /// The point, base frame, m.
    pub at_m: [f64; 3],
    /// The measured displacement, base frame, m; `null` when not measured.
    pub measured_m: Option<[f64; 3]>,
    /// The predicted displacement, base frame, m; `null` when not predicted.
    pub predicted_m: Option<[f64; 3]>,
}

/// A point of a path and its predicted error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct PathPoint {
    /// The point, base frame, m.
    pub at_m: [f64; 3],
    /// The error predicted there, m.
    pub error_m: f64,
}

/// An obstacle of the cell.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
pub struct Obstacle {
    /// Its name in the setup.
    pub name: String,
    /// Lowest corner, m: base frame, or the box's own frame when it has `frames`.
    pub min_m: [f64; 3],
    /// Highest corner, m: base frame, or the box's own frame when it has `frames`.
    pub max_m: [f64; 3],
    /// The positioner axis that carries it (`[[cell.obstacle]] carried_by`); `null` for a box
    /// that stands in the cell.
    pub carried_by: Option<String>,
    /// For a box that moves with the external axes or stands turned (carried, or frozen at a
    /// station): its frame in each posture, in the order of [`Scene::postures`] (the box is
    /// the points `R x + t` of `x` between `min_m` and `max_m`): the positioner's pose through
    /// the carrying axis at the posture's external values ([`stiffid_core::setup::Obstacle::at`]).
    /// Empty for a box that stands as given, axis-aligned in the base frame.
    pub frames: Vec<Frame>,
}

/// What to draw besides the setup and its postures.
#[derive(Debug, Clone, Default)]
pub struct Extras<'a> {
    /// The compliance of every parameter of the setup's model (rad/Nm, m/N; drives first) for the
    /// ellipsoids; `None`: no ellipsoids.
    pub compliance: Option<&'a DVector<f64>>,
    /// The force the ellipsoids are scaled to, N; `None`: the setup's rope load.
    pub force: Option<f64>,
    /// The measured displacement of each measuring point in each posture, base frame, m
    /// (`[posture][point]`; empty: none measured).
    pub measured: &'a [Vec<Vector3<f64>>],
    /// The predicted displacement of each measuring point in each posture, base frame, m
    /// (`[posture][point]`; empty: none predicted).
    pub predicted: &'a [Vec<Vector3<f64>>],
    /// A path and its predicted error.
    pub path: &'a [PathPoint],
    /// What the path's error is, in words.
    pub path_error: &'a str,
    /// Whether the scene has the rope (a measurement campaign: the plan, identification).
    pub rope: bool,
    /// What `measured` and `predicted` are, in words; `None`: the measured and the predicted
    /// displacement.
    pub arrow_names: Option<[&'a str; 2]>,
    /// The external axes' values of each posture (SI, the cell's order; empty: all at zero).
    /// The arm stands on its carriage there (frames in the cell frame,
    /// [`stiffid_core::Robot::frames_at`]); the lines of sight's margins are the cell's checks at the
    /// axis angles alone.
    pub external: &'a [Vec<f64>],
}

/// The scene of the postures `postures` (axis angles, rad) of `setup`.
///
/// # Errors
/// [`stiffid_core::Error::InvalidField`] (field `postures`) for no posture or more than
/// [`MAX_POSTURES`]; displacements (fields `measured`, `predicted`) not one list per posture of
/// one per measuring point, or not finite; a non-finite or negative force (field `force`);
/// external values not one list per posture within the axes' limits (field `external`); the
/// errors of [`Setup::check_bodies`].
pub fn scene(
    setup: &Setup,
    postures: &[Vector6<f64>],
    extras: &Extras,
) -> stiffid_core::Result<Scene> {
    let invalid = |field: &str, message: String| stiffid_core::Error::InvalidField {
        field: field.to_string(),
        message,
    };
    if postures.is_empty() || postures.len() > MAX_POSTURES {
        let n = postures.len();
        return Err(invalid(
            "postures",
            format!("{n} postures: expected 1 to {MAX_POSTURES}"),
        ));
    }
    let points = setup.tool().measuring_points.len();
    for (field, lists) in [
        ("measured", extras.measured),
        ("predicted", extras.predicted),
    ] {
        let each = lists.iter().all(|l| l.len() == points);
        if !lists.is_empty() && (lists.len() != postures.len() || !each) {
            return Err(invalid(
                field,
                format!(
                    "{} lists: expected one per posture ({}) of one displacement per measuring point ({points})",
                    lists.len(),
                    postures.len()
                ),
            ));
        }
        if !lists
            .iter()
            .flatten()
            .all(|d| d.iter().all(|v| v.is_finite()))
        {
            return Err(invalid(field, "a displacement is not finite".into()));
        }
    }
    check_external(setup, postures.len(), extras.external)?;
    let force = extras.force.unwrap_or(setup.load().load);
    if !force.is_finite() || force < 0.0 {
        return Err(invalid("force", format!("{force} N: expected >= 0")));
    }
    setup.check_bodies()?;
    let checker = Checker::new(setup);
    let drawn = Drawn {
        setup,
        checker: &checker,
        extras,
        force,
    };
    let obstacles = obstacles(setup, extras.external, postures.len());
    let postures = postures
        .iter()
        .enumerate()
        .map(|(i, q)| drawn.posture(i, q))
        .collect();
    let frames = setup.robot().frames(&Vector6::zeros());
    let (path, thinned) = thin(extras.path);
    let mut notes = Vec::new();
    if setup
        .shapes()
        .is_some_and(|g| g.shapes.iter().any(|s| s.mesh.is_some()))
    {
        notes
            .push("meshes are drawn as their convex hulls (as the cell's checks take them)".into());
    }
    if thinned {
        notes.push(format!(
            "the path's {} points are drawn as {}",
            extras.path.len(),
            path.len()
        ));
    }
    Ok(Scene {
        setup: setup.name().to_string(),
        robot: setup.robot().name().to_string(),
        links: [
            geometry::links(setup.arm(), &frames),
            external::links(setup.robot()),
        ]
        .concat(),
        postures,
        floor_z_m: setup.cell().and_then(|c| c.floor_z),
        obstacles,
        tracker_m: setup.tracker().map(|t| array(&t.position)),
        anchor_m: extras.rope.then(|| array(&setup.load().anchor)),
        ellipsoid_force_n: force,
        path,
        path_error: extras.path_error.to_string(),
        arrow_names: extras
            .arrow_names
            .unwrap_or(["measured displacement", "predicted displacement"])
            .map(String::from),
        notes,
    })
}

/// The parts of a scene's build.
struct Drawn<'a> {
    setup: &'a Setup,
    checker: &'a Checker<'a>,
    extras: &'a Extras<'a>,
    force: f64,
}

impl Drawn<'_> {
    fn posture(&self, i: usize, q: &Vector6<f64>) -> Posture {
        let (setup, tool) = (self.setup, self.setup.tool());
        let e = (self.extras.external.get(i).cloned())
            .unwrap_or_else(|| external::zero(setup.robot().external()));
        let frames = setup.robot().frames_at(q, &e);
        let mut link_frames: Vec<Frame> = geometry::parts()
            .iter()
            .map(|p| frame(&geometry::frame(&frames, *p)))
            .collect();
        link_frames.extend(external::frames(setup.robot(), &e));
        let margins = self.checker.margins_at(q, &e);
        let sights = match setup.tracker() {
            None => Vec::new(),
            Some(_) => (0..tool.measuring_points.len())
                .map(|m| Sight {
                    to_m: array(&frames.point(&tool.measuring_points[m])),
                    margin_m: margins
                        .iter()
                        .filter(|g| g.kind == CheckKind::LineOfSight)
                        .filter(|g| {
                            g.between.0 == Thing::Sight(m) || g.between.1 == Thing::Sight(m)
                        })
                        .map(|g| g.margin)
                        .fold(f64::INFINITY, f64::min),
                })
                .collect(),
        };
        Posture {
            q_deg: std::array::from_fn(|a| q[a].to_degrees()),
            external: e,
            link_frames,
            joint_positions_m: std::array::from_fn(|j| array(&frames.joints[j].translation.vector)),
            flange_m: array(&frames.flange.translation.vector),
            tcp_m: array(&frames.point(&tool.tcp)),
            loading_point_m: array(&frames.point(&tool.loading_point)),
            measuring_points_m: tool
                .measuring_points
                .iter()
                .map(|p| array(&frames.point(p)))
                .collect(),
            sights,
            ellipsoid: self.extras.compliance.and_then(|h| {
                let c = cartesian::compliance(setup.arm(), &frames, &tool.tcp, h);
                ellipsoid(
                    &c.fixed_view::<3, 3>(0, 0).into(),
                    &frames.point(&tool.tcp),
                    self.force,
                )
            }),
            arrows: (0..tool.measuring_points.len())
                .map(|m| Arrow {
                    at_m: array(&frames.point(&tool.measuring_points[m])),
                    measured_m: self.extras.measured.get(i).map(|d| array(&d[m])),
                    predicted_m: self.extras.predicted.get(i).map(|d| array(&d[m])),
                })
                .collect(),
            feasible: self
                .checker
                .constrains()
                .then(|| margins.iter().all(|m| m.margin >= 0.0)),
        }
    }
}

/// The ellipsoid of the translational compliance `c` (3x3, m/N) at `centre` scaled to `force`;
/// `None` when `c` is not finite.
pub(crate) fn ellipsoid(c: &Matrix3<f64>, centre: &Vector3<f64>, force: f64) -> Option<Ellipsoid> {
    if !c.iter().all(|v| v.is_finite()) {
        return None;
    }
    let e = SymmetricEigen::new(*c);
    let mut order = [0, 1, 2];
    order.sort_by(|&a, &b| e.eigenvalues[a].total_cmp(&e.eigenvalues[b]));
    let values: [f64; 3] = order.map(|k| e.eigenvalues[k]);
    Some(Ellipsoid {
        centre_m: array(centre),
        compliance_m_per_n: values,
        axes: order.map(|k| array(&e.eigenvectors.column(k).into())),
        semi_axes_m: values.map(|v| force * v.max(0.0)),
    })
}

/// Refuses external values `e` (per posture) unless empty or one list per posture of values
/// within the robot's external axes' limits.
pub fn check_external(setup: &Setup, postures: usize, e: &[Vec<f64>]) -> stiffid_core::Result<()> {
    if e.is_empty() {
        return Ok(());
    }
    let Some(axes) = setup.robot().external().filter(|_| e.len() == postures) else {
        return Err(stiffid_core::Error::InvalidField {
            field: "external".into(),
            message: format!(
                "{} lists: expected one per posture ({postures}) of a robot with external axes",
                e.len()
            ),
        });
    };
    e.iter()
        .enumerate()
        .try_for_each(|(i, v)| axes.check(v, &format!("external[{i}]")))
}

/// The cell's obstacles, each that moves or stands turned with its frame in each of `postures`
/// postures at its external values `external` (empty: every axis at 0).
fn obstacles(setup: &Setup, external: &[Vec<f64>], postures: usize) -> Vec<Obstacle> {
    let Some(cell) = setup.cell() else {
        return Vec::new();
    };
    let axes = setup.robot().external();
    let frames = |o: &stiffid_core::setup::Obstacle| -> Vec<Frame> {
        if o.carried_by.is_none() && o.pose == Isometry3::identity() {
            return Vec::new();
        }
        (0..postures)
            .map(|i| external.get(i).map_or(&[][..], Vec::as_slice))
            .map(|e| frame(&o.at(axes, e).pose))
            .collect()
    };
    cell.obstacles
        .iter()
        .map(|o| Obstacle {
            name: o.name.clone(),
            min_m: array(&o.min),
            max_m: array(&o.max),
            carried_by: o.carried_by.clone(),
            frames: frames(o),
        })
        .collect()
}

/// At most [`MAX_PATH_POINTS`] points of `path`, evenly spaced, the first and last kept;
/// whether any was left out.
fn thin(path: &[PathPoint]) -> (Vec<PathPoint>, bool) {
    let n = path.len();
    if n <= MAX_PATH_POINTS {
        return (path.to_vec(), false);
    }
    let last = MAX_PATH_POINTS - 1;
    let kept = (0..=last).map(|k| path[k * (n - 1) / last]).collect();
    (kept, true)
}

/// An isometry as a [`Frame`].
fn frame(t: &Isometry3<f64>) -> Frame {
    let q = t.rotation.coords;
    Frame {
        translation_m: array(&t.translation.vector),
        rotation_xyzw: [q.x, q.y, q.z, q.w],
    }
}

fn array(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}
