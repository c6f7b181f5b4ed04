//! The robot's own collision geometry from a URDF's `<collision>` elements: boxes, cylinders,
//! spheres, capsules and meshes (STL, binary or ASCII, read by `stl_io`), each a convex shape
//! (a mesh by its convex hull, parry's `ConvexPolyhedron`) with its origin in the frame of the
//! body that carries it.
//!
//! Bodies are numbered as the chain moves them: 0 the base (every link before the first revolute
//! joint, in the robot's base frame), `i = 1..=6` the links after revolute joint `i` (in its frame,
//! [`crate::Frames::joints`]`[i - 1]`). Links hung from a chain link by fixed joints (a flange,
//! `tool0`, the `base` leaf of ROS-Industrial URDFs) belong to that body, their fixed transforms
//! folded into the origins; links under other joints off the chain (a counterbalance driven by
//! `<mimic>` joints) are left out and named in [`CollisionGeometry::skipped`].
//!
//! Mesh files are found relative to the URDF's directory; `package://NAME/PATH` is looked for as
//! `DIR/NAME/PATH` in each package directory in turn (the ROS convention); `file://PATH` is a path.
//! The caller reads files: `read(path)` returns `None` when nothing exists there.

use crate::common::limits::{self, short};
use crate::{Error, Result};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use parry3d_f64::shape::{self, Ball, ConvexPolyhedron, Cuboid, Cylinder};
use std::collections::HashMap;
use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use urdf_rs::{Geometry, JointType};

/// Most triangles read from one mesh file: the convex hull of a mesh whose every vertex is on its
/// hull (a finely tessellated sphere) takes about 1 s at 80 000 triangles and 23 s at 320 000
/// on one core, so a finer mesh is refused, asking for a decimated one (ROS-Industrial collision
/// meshes have hundreds to a few thousand triangles).
pub(crate) const MAX_MESH_TRIANGLES: usize = 100_000;

/// A convex shape in its own frame, m.
#[derive(Debug, Clone)]
pub enum Shape {
    /// A box centred on the origin, half extents.
    Cuboid(Cuboid),
    /// A cylinder about the z axis centred on the origin (URDF's convention).
    Cylinder(Cylinder),
    /// A sphere at the origin.
    Ball(Ball),
    /// A capsule about the z axis centred on the origin.
    Capsule(shape::Capsule),
    /// The convex hull of a mesh.
    Convex(Arc<ConvexPolyhedron>),
}

/// parry's cylinders and capsules turn about y; URDF's about z.
fn y_to_z() -> Isometry3<f64> {
    Isometry3::rotation(Vector3::x() * std::f64::consts::FRAC_PI_2)
}

impl Shape {
    /// The shape as parry queries take it, and the transform from parry's frame of it to ours.
    pub fn parry(&self) -> (&dyn shape::Shape, Isometry3<f64>) {
        match self {
            Shape::Cuboid(s) => (s, Isometry3::identity()),
            Shape::Cylinder(s) => (s, y_to_z()),
            Shape::Ball(s) => (s, Isometry3::identity()),
            Shape::Capsule(s) => (s, y_to_z()),
            Shape::Convex(s) => (s.as_ref(), Isometry3::identity()),
        }
    }
}

/// One collision shape of the robot.
#[derive(Debug, Clone)]
pub struct LinkShape {
    /// The body that carries it: 0 the base, 1..=6 the link after revolute joint `i`.
    pub body: usize,
    /// The URDF link it comes from.
    pub link: String,
    /// The mesh file as the URDF names it (`package://...`), for a mesh; `None` for a primitive.
    pub mesh: Option<String>,
    /// Its pose in the body's frame, m.
    pub origin: Isometry3<f64>,
    /// The shape.
    pub shape: Shape,
    /// A sphere holding the shape, in the body's frame: centre and radius, m.
    pub bound: (Vector3<f64>, f64),
}

/// Every collision shape of the chain's links.
#[derive(Debug, Clone, Default)]
pub struct CollisionGeometry {
    /// The shapes, base first, in URDF order within a body.
    pub shapes: Vec<LinkShape>,
    /// Links with collision elements that hang off the chain under a non-fixed joint.
    pub skipped: Vec<String>,
}

/// Distances beyond this (m) are not worked out: nothing in a robot cell is that far.
pub(crate) const FAR: f64 = 1e4;

/// The collision geometry of the URDF `text` (read from `source_name`, in `dir`) along the chain
/// to `tip` (as [`super::urdf::parse`] chooses it); meshes read by `read`, `package://` URLs
/// resolved in `package_paths`.
///
/// # Errors
/// Those of [`super::urdf::parse`] for the text; [`Error::MeshNotFound`] naming the URDF, the link
/// and the mesh for a `package://` URL whose package is in none of the package paths (naming the
/// package and the paths) or a mesh file that does not exist; [`Error::Parse`] naming the URDF, the
/// link and the mesh: a mesh file that cannot be read or is no STL, more than 100 000 triangles, a
/// mesh format other than STL, points that span no volume, non-finite or out-of-range sizes.
pub fn parse(
    text: &str,
    source_name: &str,
    dir: &Path,
    tip: Option<&str>,
    package_paths: &[PathBuf],
    read: &dyn Fn(&Path) -> Option<Result<Vec<u8>>>,
) -> Result<CollisionGeometry> {
    super::urdf::parse(text, source_name, tip)?;
    let urdf = urdf_rs::read_from_string(text).map_err(|e| Error::Parse {
        source_name: source_name.to_string(),
        message: limits::one_line(&e.to_string()),
    })?;
    let chain_error = |message: String| Error::Chain {
        source_name: source_name.to_string(),
        message,
    };
    let tip = match tip {
        Some(t) => t.to_string(),
        None => {
            let by_child = super::urdf::tree(&urdf).map_err(chain_error)?;
            super::urdf::default_tip(&urdf, &by_child).map_err(chain_error)?
        }
    };
    let bodies = link_bodies(&urdf, &tip);
    let context = Context {
        source_name,
        dir,
        package_paths,
        read,
    };
    let mut out = CollisionGeometry::default();
    for link in &urdf.links {
        let Some((body, pose)) = bodies.get(link.name.as_str()) else {
            if !link.collision.is_empty() {
                out.skipped.push(link.name.clone());
            }
            continue;
        };
        for c in &link.collision {
            let origin = pose * origin(&c.origin, &link.name, source_name)?;
            let shape = context.shape(&c.geometry, &link.name)?;
            let (parry, fix) = shape.parry();
            let sphere = parry.compute_bounding_sphere(&(origin * fix));
            out.shapes.push(LinkShape {
                body: *body,
                link: link.name.clone(),
                mesh: match &c.geometry {
                    Geometry::Mesh { filename, .. } => Some(filename.clone()),
                    _ => None,
                },
                origin,
                shape,
                bound: (sphere.center.coords, sphere.radius),
            });
        }
    }
    out.shapes.sort_by_key(|s| s.body);
    Ok(out)
}

/// Every link moved with the chain: its body and its pose in the body's frame.
fn link_bodies<'a>(
    urdf: &'a urdf_rs::Robot,
    tip: &'a str,
) -> HashMap<&'a str, (usize, Isometry3<f64>)> {
    let by_child: HashMap<&str, &urdf_rs::Joint> = urdf
        .joints
        .iter()
        .map(|j| (j.child.link.as_str(), j))
        .collect();
    let mut chain = vec![tip];
    while let Some(j) = by_child.get(chain.last().copied().unwrap_or("")) {
        chain.push(j.parent.link.as_str());
    }
    chain.reverse();
    let mut out = HashMap::new();
    let (mut body, mut pose) = (0, Isometry3::identity());
    for (k, link) in chain.iter().enumerate() {
        if k > 0 {
            let j = by_child[link];
            match j.joint_type {
                JointType::Fixed => pose *= pose_of(&j.origin),
                _ => (body, pose) = (body + 1, Isometry3::identity()),
            }
        }
        out.insert(*link, (body, pose));
    }
    // Links hung by fixed joints from a chain link (repeat until nothing is added).
    loop {
        let added: Vec<(&str, (usize, Isometry3<f64>))> = urdf
            .joints
            .iter()
            .filter(|j| {
                j.joint_type == JointType::Fixed && !out.contains_key(j.child.link.as_str())
            })
            .filter_map(|j| {
                let (b, p) = out.get(j.parent.link.as_str())?;
                Some((j.child.link.as_str(), (*b, p * pose_of(&j.origin))))
            })
            .collect();
        if added.is_empty() {
            return out;
        }
        out.extend(added);
    }
}

fn pose_of(p: &urdf_rs::Pose) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(p.xyz[0], p.xyz[1], p.xyz[2]),
        UnitQuaternion::from_euler_angles(p.rpy[0], p.rpy[1], p.rpy[2]),
    )
}

fn origin(p: &urdf_rs::Pose, link: &str, source_name: &str) -> Result<Isometry3<f64>> {
    let field = |f: &str| {
        format!(
            "{source_name}: link '{}': collision origin {f}",
            short(link)
        )
    };
    limits::check(&field("xyz"), &p.xyz[..], &limits::LENGTH_M)?;
    limits::check(&field("rpy"), &p.rpy[..], &limits::ANGLE_RAD)?;
    Ok(pose_of(p))
}

/// Where meshes are looked for, and how files are read.
struct Context<'a> {
    source_name: &'a str,
    dir: &'a Path,
    package_paths: &'a [PathBuf],
    read: &'a dyn Fn(&Path) -> Option<Result<Vec<u8>>>,
}

impl Context<'_> {
    fn error(&self, link: &str, message: String) -> Error {
        Error::Parse {
            source_name: self.source_name.to_string(),
            message: format!("link '{}': {message}", short(link)),
        }
    }

    fn shape(&self, g: &Geometry, link: &str) -> Result<Shape> {
        let size = |name: &str, v: &[f64]| -> Result<()> {
            match v
                .iter()
                .all(|x| x.is_finite() && *x > 0.0 && *x <= limits::LENGTH_M.max)
            {
                true => Ok(()),
                false => Err(self.error(
                    link,
                    format!("collision {name} {v:?}: expected lengths > 0 and <= 100 m"),
                )),
            }
        };
        Ok(match g {
            Geometry::Box { size: s } => {
                size("box size", &s[..])?;
                Shape::Cuboid(Cuboid::new(Vector3::new(s[0], s[1], s[2]) / 2.0))
            }
            Geometry::Cylinder { radius, length } => {
                size("cylinder radius, length", &[*radius, *length])?;
                Shape::Cylinder(Cylinder::new(length / 2.0, *radius))
            }
            Geometry::Capsule { radius, length } => {
                size("capsule radius, length", &[*radius, *length])?;
                Shape::Capsule(shape::Capsule::new_y(length / 2.0, *radius))
            }
            Geometry::Sphere { radius } => {
                size("sphere radius", &[*radius])?;
                Shape::Ball(Ball::new(*radius))
            }
            Geometry::Mesh { filename, scale } => {
                let scale = scale.map_or([1.0; 3], |s| [s[0], s[1], s[2]]);
                size("mesh scale", &scale)?;
                self.mesh(filename, scale, link)?
            }
        })
    }

    fn mesh(&self, filename: &str, scale: [f64; 3], link: &str) -> Result<Shape> {
        let name = short(filename);
        if !filename.to_ascii_lowercase().ends_with(".stl") {
            return Err(self.error(
                link,
                format!("mesh '{name}': only STL meshes are read (convert it to STL)"),
            ));
        }
        let (path, bytes) = self.find(filename, link)?;
        let shown = short(&path.display().to_string());
        let bad = |m: String| self.error(link, format!("mesh {shown}: {m}"));
        binary_size(&bytes).map_err(bad)?;
        let mut cursor = Cursor::new(bytes);
        let reader = stl_io::create_stl_reader(&mut cursor)
            .map_err(|e| bad(format!("not an STL file ({e})")))?;
        let mut points = Vec::new();
        for (k, triangle) in reader.enumerate() {
            if k == MAX_MESH_TRIANGLES {
                return Err(bad(format!(
                    "more than {MAX_MESH_TRIANGLES} triangles: decimate the collision mesh (its \
                     convex hull is what the checks use; collision meshes have hundreds to a few \
                     thousand triangles)"
                )));
            }
            let t = triangle.map_err(|e| bad(format!("not an STL file ({e})")))?;
            for v in t.vertices {
                let p = Point3::new(
                    f64::from(v[0]) * scale[0],
                    f64::from(v[1]) * scale[1],
                    f64::from(v[2]) * scale[2],
                );
                if !p.iter().all(|c| limits::LENGTH_M.contains(*c)) {
                    return Err(bad(format!(
                        "a vertex {:?} outside +-100 m",
                        p.coords.as_slice()
                    )));
                }
                points.push(p);
            }
        }
        if flat(&points) {
            return Err(bad(
                "its points span no volume (empty, or flat: all in one plane)".into(),
            ));
        }
        points.sort_by(|a, b| {
            a.iter()
                .map(|c| c.to_bits())
                .cmp(b.iter().map(|c| c.to_bits()))
        });
        points.dedup();
        ConvexPolyhedron::from_convex_hull(&points)
            .map(|c| Shape::Convex(Arc::new(c)))
            .ok_or_else(|| bad("its points span no volume (empty or flat)".into()))
    }

    /// The mesh file named by `filename` and its bytes.
    fn find(&self, filename: &str, link: &str) -> Result<(PathBuf, Vec<u8>)> {
        let candidates: Vec<PathBuf> = if let Some(rest) = filename.strip_prefix("package://") {
            let package = rest.split('/').next().unwrap_or("");
            if self.package_paths.is_empty() {
                return Err(self.not_found(
                    link,
                    format!(
                        "mesh '{}' is in package '{}': give the directory that holds the \
                         package as a package path",
                        short(filename),
                        short(package)
                    ),
                ));
            }
            self.package_paths.iter().map(|p| p.join(rest)).collect()
        } else if let Some(path) = filename.strip_prefix("file://") {
            vec![PathBuf::from(path)]
        } else {
            vec![self.dir.join(filename)]
        };
        for path in &candidates {
            if let Some(bytes) = (self.read)(path) {
                return Ok((path.clone(), bytes?));
            }
        }
        let tried: Vec<String> = candidates.iter().map(|p| p.display().to_string()).collect();
        let message = match filename.strip_prefix("package://") {
            Some(rest) => format!(
                "mesh '{}': package '{}' not found in the package paths (no {})",
                short(filename),
                short(rest.split('/').next().unwrap_or("")),
                short(&tried.join(", "))
            ),
            None => format!(
                "mesh '{}': no file {}",
                short(filename),
                short(&tried.join(", "))
            ),
        };
        Err(self.not_found(link, message))
    }

    /// [`Error::MeshNotFound`] for the mesh of `link`.
    fn not_found(&self, link: &str, message: String) -> Error {
        match self.error(link, message) {
            Error::Parse {
                source_name,
                message,
            } => Error::MeshNotFound {
                source_name,
                message,
            },
            e => e,
        }
    }
}

/// Whether `points` span no volume: none, or all within a plane (their spread across the
/// thinnest direction at most [`FLAT`] of the spread along the widest, from the eigenvalues of
/// their covariance; STL's f32 coordinates leave a plane rotated in space that much out of it).
fn flat(points: &[Point3<f64>]) -> bool {
    if points.len() < 4 {
        return true;
    }
    let n = points.len() as f64;
    let mean = points.iter().map(|p| p.coords).sum::<Vector3<f64>>() / n;
    let covariance = points
        .iter()
        .map(|p| (p.coords - mean) * (p.coords - mean).transpose())
        .sum::<nalgebra::Matrix3<f64>>()
        / n;
    let eigen = covariance.symmetric_eigenvalues();
    let (thin, wide) = (eigen.min().max(0.0).sqrt(), eigen.max().max(0.0).sqrt());
    thin <= FLAT * wide
}

/// The relative thickness below which a mesh is flat ([`flat`]).
const FLAT: f64 = 1e-6;

/// Checks a binary STL's size against the triangle count of its header (84 bytes, then 50 per
/// triangle): a header claiming fewer triangles would leave the rest unread, more would read past
/// the end. An ASCII STL (first line `solid ...`, as `stl_io` tells them) passes.
fn binary_size(bytes: &[u8]) -> std::result::Result<(), String> {
    let first = bytes.split(|b| *b == b'\n').next().unwrap_or(&[]);
    if first.starts_with(b"solid ") && std::str::from_utf8(first).is_ok() {
        return Ok(());
    }
    let Some(count) = bytes.get(80..84) else {
        return Err(format!(
            "not an STL file ({} bytes, a binary STL has at least 84)",
            bytes.len()
        ));
    };
    let count = u32::from_le_bytes([count[0], count[1], count[2], count[3]]);
    let expected = 84 + 50 * u64::from(count);
    match bytes.len() as u64 == expected {
        true => Ok(()),
        false => Err(format!(
            "its header says {count} triangles ({expected} bytes), but the file holds {} bytes \
             (a binary STL is 84 bytes and 50 per triangle): a damaged or mislabelled file",
            bytes.len()
        )),
    }
}

#[cfg(test)]
mod collision_tests;
