//! The scene-file form of a CSG tree (`NodeSpec`, deserialised from TOML) and its resolution into the
//! runtime `Node` with material indices and transforms.
//!
//! A node is a table with exactly one shape or operation key, and optionally `material` and
//! `transform` beside it:
//!
//! ```toml
//! csg = { difference = [
//!     { box = { min = [-1, -1, -1], max = [1, 1, 1] }, material = "steel" },
//!     { sphere = { center = [0, 0, 0], radius = 1.3 }, transform = { scale = [1, 2, 1] } },
//! ], material = "paint" }
//! ```
//!
//! Shapes: `sphere { center = [0,0,0], radius }`; `box { min, max }`; `cylinder { radius, height }`
//! (axis y, centred on the origin) or `cylinder { base, top, radius }`; `cone { radius, height }`
//! (base disc at y = -height/2, apex at +height/2) or `cone { base, apex, radius }`;
//! `torus { major_radius, minor_radius }` (around the y axis); `halfspace { normal, offset }` (the
//! solid `normal . p <= offset`) or `halfspace { normal, point }`; `mesh = "name"`, a closed mesh
//! of the scene as an operand (resolved with `NodeSpec::resolve_with`). Operations `union`,
//! `intersection`, `difference` take arrays of one or more nodes (difference: the first minus all
//! others). A node without `material` takes its parent's (the root's default comes from the caller).
//! Unknown keys are errors.

use std::fmt;

use glam::{Mat4, Quat, Vec3};
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use std::sync::Arc;

use crate::csg::{Node, Op, Shape, SolidMesh};
use crate::scene::transform::TransformSpec;

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    #[serde(default)]
    pub center: [f32; 3],
    pub radius: f32,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: [f32; 3],
    pub max: [f32; 3],
}

/// Cylinder or cone: `radius` with either `height` (on the y axis, centred) or two end points.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxialSpec {
    pub radius: f32,
    pub height: Option<f32>,
    pub base: Option<[f32; 3]>,
    /// The far end: `top` of a cylinder, or `apex` of a cone.
    #[serde(alias = "apex")]
    pub top: Option<[f32; 3]>,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorusSpec {
    pub major_radius: f32,
    pub minor_radius: f32,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HalfSpaceSpec {
    pub normal: [f32; 3],
    pub offset: Option<f32>,
    pub point: Option<[f32; 3]>,
}

/// What a node is: a primitive or an operation over child nodes.
#[derive(Clone, Debug, PartialEq)]
pub enum KindSpec {
    Sphere(SphereSpec),
    Box(BoxSpec),
    Cylinder(AxialSpec),
    Cone(AxialSpec),
    Torus(TorusSpec),
    HalfSpace(HalfSpaceSpec),
    /// A closed mesh of the scene, by name.
    Mesh(String),
    Union(Vec<NodeSpec>),
    Intersection(Vec<NodeSpec>),
    Difference(Vec<NodeSpec>),
}

/// One node of a CSG tree as written in a scene file.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeSpec {
    pub kind: KindSpec,
    pub material: Option<String>,
    pub transform: Option<TransformSpec>,
}

const KEYS: &[&str] = &[
    "sphere",
    "box",
    "cylinder",
    "cone",
    "torus",
    "halfspace",
    "mesh",
    "union",
    "intersection",
    "difference",
    "material",
    "transform",
];

impl<'de> Deserialize<'de> for NodeSpec {
    fn deserialize<D: Deserializer<'de>>(de: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = NodeSpec;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a CSG node: a table with one of sphere, box, cylinder, cone, torus, halfspace, union, intersection, difference")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<NodeSpec, A::Error> {
                let mut kind: Option<KindSpec> = None;
                let mut material = None;
                let mut transform = None;
                while let Some(key) = map.next_key::<String>()? {
                    let k = match key.as_str() {
                        "material" => {
                            if material.is_some() {
                                return Err(de::Error::duplicate_field("material"));
                            }
                            material = Some(map.next_value::<String>()?);
                            continue;
                        }
                        "transform" => {
                            if transform.is_some() {
                                return Err(de::Error::duplicate_field("transform"));
                            }
                            transform = Some(map.next_value::<TransformSpec>()?);
                            continue;
                        }
                        "sphere" => KindSpec::Sphere(map.next_value()?),
                        "box" => KindSpec::Box(map.next_value()?),
                        "cylinder" => KindSpec::Cylinder(map.next_value()?),
                        "cone" => KindSpec::Cone(map.next_value()?),
                        "torus" => KindSpec::Torus(map.next_value()?),
                        "halfspace" => KindSpec::HalfSpace(map.next_value()?),
                        "mesh" => KindSpec::Mesh(map.next_value()?),
                        "union" => KindSpec::Union(map.next_value()?),
                        "intersection" => KindSpec::Intersection(map.next_value()?),
                        "difference" => KindSpec::Difference(map.next_value()?),
                        other => return Err(de::Error::unknown_field(other, KEYS)),
                    };
                    if kind.is_some() {
                        return Err(de::Error::custom(format!(
                            "a CSG node has exactly one shape or operation (found a second: `{key}`)"
                        )));
                    }
                    kind = Some(k);
                }
                let kind = kind.ok_or_else(|| {
                    de::Error::custom("a CSG node needs one of sphere, box, cylinder, cone, torus, halfspace, union, intersection, difference")
                })?;
                Ok(NodeSpec {
                    kind,
                    material,
                    transform,
                })
            }
        }
        de.deserialize_map(V)
    }
}

/// Why a CSG tree of a scene file cannot be resolved; `what` is the shape, `name` its field.
#[derive(Debug, thiserror::Error)]
pub enum CsgSpecError {
    #[error("{what}: {name} must be a positive number (got {value})")]
    NotPositive {
        what: &'static str,
        name: &'static str,
        value: f32,
    },
    #[error("{what}: {name} must be finite")]
    NotFinite {
        what: &'static str,
        name: &'static str,
    },
    #[error("{0}: give either `height` or both `base` and `top`/`apex`")]
    AxialSize(&'static str),
    #[error("CSG node: unknown material '{0}'")]
    UnknownMaterial(String),
    #[error("CSG node: unknown mesh '{0}'")]
    UnknownMesh(String),
    #[error("csg {}: needs at least one operand", format!("{:?}", .0).to_lowercase())]
    NoOperands(Op),
    #[error("box: min {min} must be below max {max} on every axis")]
    BoxOrder { min: Vec3, max: Vec3 },
    #[error("halfspace: normal must not be zero")]
    ZeroNormal,
    #[error("halfspace: give `offset` or `point`, not both (and finite)")]
    HalfSpaceOffset,
}

fn positive(what: &'static str, name: &'static str, v: f32) -> Result<f32, CsgSpecError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(CsgSpecError::NotPositive {
            what,
            name,
            value: v,
        })
    }
}

fn finite3(what: &'static str, name: &'static str, v: [f32; 3]) -> Result<Vec3, CsgSpecError> {
    let v = Vec3::from_array(v);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(CsgSpecError::NotFinite { what, name })
    }
}

/// A y-axis shape's size and placement from `height` or from two end points.
fn axial(what: &'static str, s: &AxialSpec) -> Result<(f32, f32, Mat4), CsgSpecError> {
    let r = positive(what, "radius", s.radius)?;
    match (s.height, s.base, s.top) {
        (Some(h), None, None) => Ok((r, positive(what, "height", h)?, Mat4::IDENTITY)),
        (None, Some(b), Some(t)) => {
            let (b, t) = (finite3(what, "base", b)?, finite3(what, "top", t)?);
            let axis = t - b;
            let h = positive(what, "distance from base to top", axis.length())?;
            let rot = Quat::from_rotation_arc(Vec3::Y, axis / h);
            Ok((r, h, Mat4::from_rotation_translation(rot, (b + t) * 0.5)))
        }
        _ => Err(CsgSpecError::AxialSize(what)),
    }
}

impl NodeSpec {
    /// The runtime tree: names of materials looked up with `material_index` (an unknown name is an
    /// error), nodes without a material inheriting their parent's (`default_material` at the root).
    pub fn resolve(
        &self,
        material_index: &dyn Fn(&str) -> Option<u32>,
        default_material: u32,
    ) -> Result<Node, CsgSpecError> {
        self.resolve_with(material_index, &|_| None, default_material)
    }

    /// Levels of the tree: 1 for a shape, one more than its deepest operand for an operation.
    pub fn depth(&self) -> usize {
        match &self.kind {
            KindSpec::Union(k) | KindSpec::Intersection(k) | KindSpec::Difference(k) => {
                1 + k.iter().map(NodeSpec::depth).max().unwrap_or(0)
            }
            _ => 1,
        }
    }

    /// As `resolve`, with `mesh_solid` giving the closed mesh of a name for `mesh` operands (`None`:
    /// no such mesh).
    pub fn resolve_with(
        &self,
        material_index: &dyn Fn(&str) -> Option<u32>,
        mesh_solid: &dyn Fn(&str) -> Option<Arc<SolidMesh>>,
        default_material: u32,
    ) -> Result<Node, CsgSpecError> {
        let material = match &self.material {
            Some(name) => {
                material_index(name).ok_or_else(|| CsgSpecError::UnknownMaterial(name.clone()))?
            }
            None => default_material,
        };
        let transform = self
            .transform
            .as_ref()
            .map_or(Mat4::IDENTITY, |t| t.to_mat4());
        if let Some((shape, placed)) = self.kind.primitive()? {
            return Ok(Node::Primitive {
                shape,
                transform: transform * placed,
                material,
            });
        }
        let (op, kids) = match &self.kind {
            KindSpec::Mesh(name) => {
                return Ok(Node::Mesh {
                    mesh: mesh_solid(name)
                        .ok_or_else(|| CsgSpecError::UnknownMesh(name.clone()))?,
                    transform,
                    material,
                })
            }
            KindSpec::Union(k) => (Op::Union, k),
            KindSpec::Intersection(k) => (Op::Intersection, k),
            KindSpec::Difference(k) => (Op::Difference, k),
            _ => unreachable!("primitives are resolved above"),
        };
        if kids.is_empty() {
            return Err(CsgSpecError::NoOperands(op));
        }
        let children = kids
            .iter()
            .map(|k| k.resolve_with(material_index, mesh_solid, material))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Node::Operation {
            op,
            children,
            transform,
        })
    }
}

impl KindSpec {
    /// A primitive's shape and its placement in its node's frame (`None` for meshes and
    /// operations).
    fn primitive(&self) -> Result<Option<(Shape, Mat4)>, CsgSpecError> {
        let axial_shape = |what, s, shape: fn(f32, f32) -> Shape| {
            axial(what, s).map(|(radius, height, m)| Some((shape(radius, height), m)))
        };
        let shape = match self {
            KindSpec::Sphere(s) => Shape::Sphere {
                center: finite3("sphere", "center", s.center)?,
                radius: positive("sphere", "radius", s.radius)?,
            },
            KindSpec::Box(b) => {
                let (min, max) = (finite3("box", "min", b.min)?, finite3("box", "max", b.max)?);
                if !min.cmplt(max).all() {
                    return Err(CsgSpecError::BoxOrder { min, max });
                }
                Shape::Box { min, max }
            }
            KindSpec::Cylinder(s) => {
                return axial_shape("cylinder", s, |radius, height| Shape::Cylinder {
                    radius,
                    height,
                })
            }
            KindSpec::Cone(s) => {
                return axial_shape("cone", s, |radius, height| Shape::Cone { radius, height })
            }
            KindSpec::Torus(t) => Shape::Torus {
                major: positive("torus", "major_radius", t.major_radius)?,
                minor: positive("torus", "minor_radius", t.minor_radius)?,
            },
            KindSpec::HalfSpace(h) => h.shape()?,
            KindSpec::Mesh(_)
            | KindSpec::Union(_)
            | KindSpec::Intersection(_)
            | KindSpec::Difference(_) => return Ok(None),
        };
        Ok(Some((shape, Mat4::IDENTITY)))
    }
}

impl HalfSpaceSpec {
    /// The unit normal and offset, from `offset` (scaled with the normal) or a `point` on the plane.
    fn shape(&self) -> Result<Shape, CsgSpecError> {
        let n = finite3("halfspace", "normal", self.normal)?;
        let len = n.length();
        if len <= 0.0 {
            return Err(CsgSpecError::ZeroNormal);
        }
        let n = n / len;
        let offset = match (self.offset, self.point) {
            (Some(o), None) if o.is_finite() => o / len,
            (None, Some(p)) => n.dot(finite3("halfspace", "point", p)?),
            (None, None) => 0.0,
            _ => return Err(CsgSpecError::HalfSpaceOffset),
        };
        Ok(Shape::HalfSpace { normal: n, offset })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize)]
    struct Holder {
        csg: NodeSpec,
    }

    fn parse(s: &str) -> Result<NodeSpec, String> {
        toml::from_str::<Holder>(s)
            .map(|h| h.csg)
            .map_err(|e| e.to_string())
    }

    fn materials(name: &str) -> Option<u32> {
        ["default", "red", "steel"]
            .iter()
            .position(|&n| n == name)
            .map(|i| i as u32)
    }

    #[test]
    fn the_issue_example_parses_and_resolves() {
        let spec = parse(
            "csg = { difference = [ { box = { min = [-1,-1,-1], max = [1,1,1] } }, { sphere = { center = [0,0,0], radius = 1.3 }, material = \"red\" } ], material = \"steel\", transform = { translate = [0, 1, 0] } }",
        )
        .unwrap();
        let node = spec.resolve(&materials, 0).unwrap();
        let Node::Operation {
            op,
            children,
            transform,
        } = node
        else {
            panic!("an operation")
        };
        assert_eq!(op, Op::Difference);
        assert_eq!(transform.transform_point3(Vec3::ZERO), Vec3::Y);
        assert!(matches!(
            children[0],
            Node::Primitive {
                material: 2,
                shape: Shape::Box { .. },
                ..
            }
        ));
        assert!(
            matches!(children[1], Node::Primitive { material: 1, shape: Shape::Sphere { radius, .. }, .. } if radius == 1.3)
        );
    }

    #[test]
    fn every_shape_parses() {
        let spec = parse(
            r#"csg = { union = [
                { cylinder = { radius = 0.5, height = 2 } },
                { cylinder = { radius = 0.5, base = [0, 0, 0], top = [0, 0, 3] } },
                { cone = { radius = 0.5, base = [0, 0, 0], apex = [1, 0, 0] } },
                { cone = { radius = 0.5, height = 1 } },
                { torus = { major_radius = 2, minor_radius = 0.25 }, transform = { rotate_x = 90 } },
                { intersection = [ { halfspace = { normal = [0, 2, 0], offset = 1 } }, { halfspace = { normal = [0, -1, 0], point = [0, -3, 0] } }, { sphere = { radius = 5 } } ] },
            ] }"#,
        )
        .unwrap();
        let node = spec.resolve(&materials, 0).unwrap();
        let obj = crate::csg::CsgObject::new(node, Mat4::IDENTITY).unwrap();
        assert_eq!(obj.materials().count(), 8);
        // The cylinder from (0,0,0) to (0,0,3): its axis is z, so it spans z in [0, 3].
        let Node::Operation { children, .. } = &obj.root else {
            panic!()
        };
        let Node::Primitive { transform, .. } = &children[1] else {
            panic!()
        };
        let top = transform.transform_point3(Vec3::new(0.0, 1.5, 0.0));
        assert!((top - Vec3::new(0.0, 0.0, 3.0)).length() < 1e-6);
    }

    #[test]
    fn bad_input_is_a_clear_error() {
        for (text, want) in [
            (
                "csg = { sphere = { radius = 1, centre = [0, 0, 0] } }",
                "centre",
            ),
            (
                "csg = { sphere = { radius = -1 } }",
                "radius must be a positive",
            ),
            ("csg = { spheer = { radius = 1 } }", "spheer"),
            (
                "csg = { sphere = { radius = 1 }, box = { min = [0,0,0], max = [1,1,1] } }",
                "exactly one",
            ),
            ("csg = { union = [] }", "at least one operand"),
            (
                "csg = { sphere = { radius = 1 }, material = \"nope\" }",
                "unknown material 'nope'",
            ),
            (
                "csg = { box = { min = [0,0,0], max = [1,-1,1] } }",
                "below max",
            ),
            ("csg = { cylinder = { radius = 1 } }", "either `height`"),
            ("csg = { material = \"red\" }", "needs one of"),
            ("csg = { mesh = \"bunny\" }", "unknown mesh 'bunny'"),
        ] {
            let err = parse(text).and_then(|s| {
                s.resolve(&materials, 0)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            });
            let e = err.expect_err(text);
            assert!(e.contains(want), "{text}: {e}");
        }
    }

    #[test]
    fn mesh_operands_resolve_by_name() {
        let cube = Arc::new(
            crate::scene::generate::box_mesh(Vec3::ZERO, Vec3::ONE)
                .to_solid()
                .unwrap(),
        );
        let spec = parse("csg = { difference = [ { mesh = \"cube\", material = \"red\" }, { sphere = { radius = 0.5 } } ] }").unwrap();
        let meshes = |name: &str| (name == "cube").then(|| cube.clone());
        let node = spec.resolve_with(&materials, &meshes, 0).unwrap();
        let Node::Operation { children, .. } = node else {
            panic!()
        };
        assert!(
            matches!(&children[0], Node::Mesh { material: 1, mesh, .. } if Arc::ptr_eq(mesh, &cube))
        );
    }
}
