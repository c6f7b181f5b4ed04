//! A scene as glTF 2.0 binary (`.glb`; Khronos, "glTF 2.0 Specification", section 4.4, the
//! binary file format): metres, one node per posture named `posture N` (1-based) holding one
//! node per link, named as [`super::Link::name`] (the URDF's link, `link K` for a DH robot,
//! `tool`), with that link frame's transform in the base frame; each link's shapes are one mesh
//! shared by every posture. glTF's y is up: the root node `stiffid base frame (z up)` turns the
//! robot's base frame (z up) into it. The JSON part is written with `gltf-json`'s types.

use super::{Geometry, Link, Scene};
use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use std::collections::BTreeMap;

/// The GLB bytes of `scene`.
pub fn glb(scene: &Scene) -> Vec<u8> {
    let mut w = Writer::default();
    let meshes: Vec<Option<json::Index<json::Mesh>>> =
        scene.links.iter().map(|l| w.mesh(l)).collect();
    let mut postures = Vec::with_capacity(scene.postures.len());
    for (i, p) in scene.postures.iter().enumerate() {
        let children = scene
            .links
            .iter()
            .zip(&p.link_frames)
            .zip(&meshes)
            .map(|((link, f), mesh)| {
                w.root.push(json::Node {
                    name: Some(link.name.clone()),
                    translation: Some(f.translation_m.map(|v| v as f32)),
                    rotation: Some(json::scene::UnitQuaternion(
                        f.rotation_xyzw.map(|v| v as f32),
                    )),
                    mesh: *mesh,
                    ..Default::default()
                })
            })
            .collect();
        postures.push(w.root.push(json::Node {
            name: Some(format!("posture {}", i + 1)),
            children: Some(children),
            ..Default::default()
        }));
    }
    // z up to glTF's y up: -90 deg about x.
    let half = std::f32::consts::FRAC_1_SQRT_2;
    let base = w.root.push(json::Node {
        name: Some("stiffid base frame (z up)".into()),
        rotation: Some(json::scene::UnitQuaternion([-half, 0.0, 0.0, half])),
        children: Some(postures),
        ..Default::default()
    });
    w.finish(scene, base)
}

/// The JSON part and the binary buffer as they are built.
#[derive(Default)]
struct Writer {
    root: json::Root,
    bin: Vec<u8>,
    materials: BTreeMap<String, json::Index<json::Material>>,
}

impl Writer {
    /// The mesh of a link's shapes; `None` for a link without shapes.
    fn mesh(&mut self, link: &Link) -> Option<json::Index<json::Mesh>> {
        let material = self.material(&link.part);
        let primitives: Vec<json::mesh::Primitive> = link
            .geometry
            .iter()
            .filter(|g| !g.triangles.is_empty())
            .map(|g| self.primitive(g, material))
            .collect();
        (!primitives.is_empty()).then(|| {
            self.root.push(json::Mesh {
                name: Some(link.name.clone()),
                primitives,
                extensions: None,
                extras: Default::default(),
                weights: None,
            })
        })
    }

    /// One material per part kind: grey links, an orange tool.
    fn material(&mut self, part: &str) -> json::Index<json::Material> {
        let (name, colour) = match part {
            "tool" => ("tool", [0.95, 0.55, 0.1, 1.0]),
            _ => ("robot", [0.72, 0.74, 0.78, 1.0]),
        };
        if let Some(m) = self.materials.get(name) {
            return *m;
        }
        let m = self.root.push(json::Material {
            name: Some(name.into()),
            double_sided: true,
            pbr_metallic_roughness: json::material::PbrMetallicRoughness {
                base_color_factor: json::material::PbrBaseColorFactor(colour),
                metallic_factor: json::material::StrengthFactor(0.1),
                roughness_factor: json::material::StrengthFactor(0.7),
                ..Default::default()
            },
            ..Default::default()
        });
        self.materials.insert(name.into(), m);
        m
    }

    fn primitive(
        &mut self,
        g: &Geometry,
        material: json::Index<json::Material>,
    ) -> json::mesh::Primitive {
        let positions: Vec<u8> = g
            .positions_m
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let indices: Vec<u8> = g
            .triangles
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let (mut min, mut max) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in &g.positions_m {
            for a in 0..3 {
                min[a] = min[a].min(p[a]);
                max[a] = max[a].max(p[a]);
            }
        }
        let position = self.accessor(
            &positions,
            json::buffer::Target::ArrayBuffer,
            (
                json::accessor::ComponentType::F32,
                json::accessor::Type::Vec3,
            ),
            g.positions_m.len(),
            Some((min, max)),
        );
        let index = self.accessor(
            &indices,
            json::buffer::Target::ElementArrayBuffer,
            (
                json::accessor::ComponentType::U32,
                json::accessor::Type::Scalar,
            ),
            3 * g.triangles.len(),
            None,
        );
        json::mesh::Primitive {
            attributes: BTreeMap::from([(Valid(json::mesh::Semantic::Positions), position)]),
            extensions: None,
            extras: Default::default(),
            indices: Some(index),
            material: Some(material),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        }
    }

    /// An accessor of `count` elements over `bytes` appended to the buffer (4-byte aligned).
    fn accessor(
        &mut self,
        bytes: &[u8],
        target: json::buffer::Target,
        (component, kind): (json::accessor::ComponentType, json::accessor::Type),
        count: usize,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> json::Index<json::Accessor> {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        let view = self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        });
        let value = |v: [f32; 3]| json::Value::from(v.to_vec());
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(kind),
            min: bounds.map(|b| value(b.0)),
            max: bounds.map(|b| value(b.1)),
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// The GLB container: a 12-byte header, the JSON chunk padded with spaces and the binary
    /// chunk padded with zeros, each to 4 bytes.
    fn finish(mut self, scene: &Scene, base: json::Index<json::Node>) -> Vec<u8> {
        self.root.asset = json::Asset {
            generator: Some(format!("stiffid {}", env!("CARGO_PKG_VERSION"))),
            version: "2.0".into(),
            ..Default::default()
        };
        let name = format!("{} on {}", scene.robot, scene.setup);
        self.root.push(json::Scene {
            name: Some(name),
            nodes: vec![base],
            extensions: None,
            extras: Default::default(),
        });
        self.root.scene = Some(json::Index::new(0));
        if !self.bin.is_empty() {
            self.root.push(json::Buffer {
                byte_length: USize64::from(self.bin.len()),
                name: None,
                uri: None,
                extensions: None,
                extras: Default::default(),
            });
        }
        let mut text = json::serialize::to_vec(&self.root).expect("glTF JSON serialises");
        pad(&mut text, b' ');
        pad(&mut self.bin, 0);
        let chunks = 8
            + text.len()
            + if self.bin.is_empty() {
                0
            } else {
                8 + self.bin.len()
            };
        let mut out = Vec::with_capacity(12 + chunks);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&u32_len(12 + chunks).to_le_bytes());
        for (kind, data) in [(*b"JSON", &text), (*b"BIN\0", &self.bin)] {
            if data.is_empty() {
                continue;
            }
            out.extend_from_slice(&u32_len(data.len()).to_le_bytes());
            out.extend_from_slice(&kind);
            out.extend_from_slice(data);
        }
        out
    }
}

/// Pads `v` to a multiple of 4 bytes with `byte`.
fn pad(v: &mut Vec<u8>, byte: u8) {
    while !v.len().is_multiple_of(4) {
        v.push(byte);
    }
}

/// A length as GLB's u32 (a scene is far below 4 GiB: [`super::MAX_POSTURES`] postures of
/// links whose meshes are convex hulls).
fn u32_len(n: usize) -> u32 {
    u32::try_from(n).expect("a scene under 4 GiB")
}
