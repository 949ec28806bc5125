//! Procedural meshes and scenes for tests and benchmarks: a subdivided icosphere (closed, watertight by
//! construction, with shared vertices), helpers that wrap meshes into a Scene, and CSG scenes (a
//! showcase of every primitive and operation, and rows of spheres as CSG or as meshes).

use std::collections::HashMap;

use glam::{Mat4, Vec3, Vec4};

use super::{Instance, Material, Mesh, Scene};
use crate::csg::{CsgObject, Node, Shape};

/// A unit icosphere with `subdivisions` levels of 4:1 splits (20 * 4^n triangles), optionally displaced
/// radially by a smooth bumpy function of amplitude `bump` (0 for a sphere).
pub fn icosphere(subdivisions: u32, bump: f32) -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut pos: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut tris: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut midpoint = |a: u32, b: u32, pos: &mut Vec<Vec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                pos.push(((pos[a as usize] + pos[b as usize]) * 0.5).normalize());
                pos.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(tris.len() * 4);
        for [a, b, c] in tris {
            let ab = midpoint(a, b, &mut pos);
            let bc = midpoint(b, c, &mut pos);
            let ca = midpoint(c, a, &mut pos);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    let normals = pos.clone();
    if bump != 0.0 {
        for p in &mut pos {
            let d = (p.x * 7.0).sin() * (p.y * 9.0).sin() * (p.z * 5.0).cos();
            *p *= 1.0 + bump * d;
        }
    }
    Mesh {
        name: format!("icosphere-{subdivisions}"),
        positions: pos,
        normals,
        indices: tris,
        ..Default::default()
    }
}

/// A grid of n x n unit quads in the z = 0 plane (2 n^2 triangles).
pub fn quad_grid(n: u32) -> Mesh {
    let mut m = Mesh::default();
    for y in 0..=n {
        for x in 0..=n {
            m.positions.push(Vec3::new(x as f32, y as f32, 0.0));
            m.normals.push(Vec3::Z);
        }
    }
    for y in 0..n {
        for x in 0..n {
            let i = y * (n + 1) + x;
            m.indices.push([i, i + 1, i + n + 2]);
            m.indices.push([i, i + n + 2, i + n + 1]);
        }
    }
    m
}

/// An axis-aligned box of 12 triangles from `lo` to `hi`.
pub fn box_mesh(lo: Vec3, hi: Vec3) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..8 {
        m.positions.push(Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        ));
        m.normals.push(Vec3::Z);
    }
    for [a, b, c, d] in [
        [0, 1, 3, 2],
        [4, 6, 7, 5],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 5, 7, 3],
    ] {
        m.indices.push([a, b, c]);
        m.indices.push([a, c, d]);
    }
    m
}

/// A scene of the given meshes and instances, all with the default material.
pub fn scene_of(meshes: Vec<Mesh>, instances: Vec<Instance>) -> Scene {
    Scene {
        meshes,
        instances,
        materials: vec![Material::default()],
        ..Default::default()
    }
}

/// A scene holding one mesh at the identity, with the default material.
pub fn single_mesh_scene(mut mesh: Mesh) -> Scene {
    mesh.material = 0;
    let triangles = mesh.indices.len();
    Scene {
        meshes: vec![mesh],
        instances: vec![Instance::new(0, Mat4::IDENTITY)],
        materials: vec![Material::default()],
        stats: super::SceneStats {
            meshes: 1,
            primitives: 1,
            triangles,
            materials: 1,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// A plain dielectric material of colour `rgb`.
pub fn matte(name: &str, rgb: [f32; 3], roughness: f32) -> Material {
    Material {
        name: name.into(),
        base_color: Vec4::new(rgb[0], rgb[1], rgb[2], 1.0),
        metallic: 0.0,
        roughness,
        ..Default::default()
    }
}

/// A square ground plane of side `size` in y = 0, centred on the origin (instance of `meshes[mesh]`).
fn ground(scene: &mut Scene, size: f32, material: u32) {
    let mut m = quad_grid(1);
    m.name = "ground".into();
    m.material = material;
    for n in &mut m.normals {
        *n = Vec3::Y;
    }
    let to_world = Mat4::from_translation(Vec3::new(-size / 2.0, 0.0, size / 2.0))
        * Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2)
        * Mat4::from_scale(Vec3::splat(size));
    scene.meshes.push(m);
    scene
        .instances
        .push(Instance::new(scene.meshes.len() as u32 - 1, to_world));
}

fn csg(node: Node, to_world: Mat4) -> CsgObject {
    CsgObject::new(node, to_world).expect("generated CSG objects are bounded")
}

fn prim(shape: Shape, material: u32) -> Node {
    Node::primitive(shape, material)
}

/// Every CSG primitive and operation on a mesh ground plane (y up): a box minus a sphere, a lens
/// (sphere n sphere), a tilted torus, a capped cylinder under a cone, a cube chamfered by a
/// half-space, and a closed mesh (an icosphere) drilled through by a cylinder.
pub fn csg_showcase() -> Scene {
    let mut s = Scene {
        materials: vec![
            matte("ground", [0.6, 0.6, 0.6], 0.8),
            matte("red", [0.8, 0.15, 0.1], 0.4),
            matte("gold", [0.9, 0.7, 0.2], 0.3),
            matte("blue", [0.15, 0.3, 0.85], 0.3),
            matte("green", [0.2, 0.7, 0.25], 0.5),
            matte("white", [0.85, 0.85, 0.85], 0.5),
        ],
        ..Default::default()
    };
    ground(&mut s, 12.0, 0);
    s.csg = showcase_back_row();
    s.csg.extend(showcase_front_row());
    s
}

/// The showcase's back row: a box minus a sphere, a lens, a tilted torus.
fn showcase_back_row() -> Vec<CsgObject> {
    let (box_, sphere) = (
        Shape::Box {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        },
        |center: Vec3, radius: f32| Shape::Sphere { center, radius },
    );
    let t = Mat4::from_translation;
    vec![
        csg(
            Node::difference(vec![prim(box_, 1), prim(sphere(Vec3::ZERO, 1.3), 2)]),
            t(Vec3::new(-3.0, 1.0, 0.0)) * Mat4::from_rotation_y(0.5),
        ),
        csg(
            Node::intersection(vec![
                prim(sphere(Vec3::new(-0.6, 0.0, 0.0), 1.0), 3),
                prim(sphere(Vec3::new(0.6, 0.0, 0.0), 1.0), 3),
            ]),
            t(Vec3::new(0.0, 0.81, 0.0)) * Mat4::from_rotation_y(1.2),
        ),
        csg(
            prim(
                Shape::Torus {
                    major: 0.8,
                    minor: 0.3,
                },
                2,
            ),
            t(Vec3::new(3.0, 1.1, 0.0)) * Mat4::from_rotation_x(1.1),
        ),
    ]
}

/// The showcase's front row: a capped cylinder under a cone, a chamfered cube, a drilled
/// icosphere.
fn showcase_front_row() -> Vec<CsgObject> {
    let t = Mat4::from_translation;
    vec![
        csg(
            Node::union(vec![
                prim(
                    Shape::Cylinder {
                        radius: 0.4,
                        height: 1.2,
                    },
                    4,
                )
                .transformed(t(Vec3::new(0.0, 0.6, 0.0))),
                prim(
                    Shape::Cone {
                        radius: 0.55,
                        height: 0.8,
                    },
                    1,
                )
                .transformed(t(Vec3::new(0.0, 1.6, 0.0))),
            ]),
            t(Vec3::new(1.6, 0.0, 2.2)),
        ),
        csg(
            Node::intersection(vec![
                prim(
                    Shape::Box {
                        min: Vec3::splat(-0.6),
                        max: Vec3::splat(0.6),
                    },
                    5,
                ),
                prim(
                    Shape::HalfSpace {
                        normal: Vec3::ONE.normalize(),
                        offset: 0.75,
                    },
                    3,
                ),
            ]),
            t(Vec3::new(-1.4, 0.6, 2.2)) * Mat4::from_rotation_y(0.4),
        ),
        csg(
            Node::difference(vec![
                Node::Mesh {
                    mesh: std::sync::Arc::new(
                        icosphere(3, 0.0)
                            .to_solid()
                            .expect("an icosphere is closed"),
                    ),
                    transform: Mat4::from_scale(Vec3::splat(0.7)),
                    material: 4,
                },
                prim(
                    Shape::Cylinder {
                        radius: 0.3,
                        height: 2.0,
                    },
                    2,
                )
                .transformed(Mat4::from_rotation_x(std::f32::consts::FRAC_PI_2)),
            ]),
            t(Vec3::new(3.3, 0.7, 2.2)) * Mat4::from_rotation_y(-0.5),
        ),
    ]
}

/// `n x n` spheres of radius 0.4 a unit apart on a ground plane: CSG spheres, or (`Some(level)`)
/// instances of one icosphere of that many subdivisions.
pub fn spheres(n: u32, tessellated: Option<u32>) -> Scene {
    let mut s = Scene {
        materials: vec![
            matte("ground", [0.6, 0.6, 0.6], 0.8),
            matte("sphere", [0.8, 0.3, 0.2], 0.4),
        ],
        ..Default::default()
    };
    ground(&mut s, n as f32 + 2.0, 0);
    let centers = (0..n * n).map(|k| {
        Vec3::new(
            (k % n) as f32 - (n - 1) as f32 / 2.0,
            0.4,
            (k / n) as f32 - (n - 1) as f32 / 2.0,
        )
    });
    match tessellated {
        Some(level) => {
            let mut m = icosphere(level, 0.0);
            m.material = 1;
            s.meshes.push(m);
            let mesh = s.meshes.len() as u32 - 1;
            for c in centers {
                s.instances.push(Instance::new(
                    mesh,
                    Mat4::from_translation(c) * Mat4::from_scale(Vec3::splat(0.4)),
                ));
            }
        }
        None => {
            for c in centers {
                s.csg.push(csg(
                    prim(
                        Shape::Sphere {
                            center: Vec3::ZERO,
                            radius: 1.0,
                        },
                        1,
                    ),
                    Mat4::from_translation(c) * Mat4::from_scale(Vec3::splat(0.4)),
                ));
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn icosphere_is_closed() {
        let m = icosphere(3, 0.0);
        assert_eq!(m.indices.len(), 20 * 64);
        // Closed 2-manifold: every edge is shared by exactly two triangles (Euler: V - E + F = 2).
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &m.indices {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        assert!(edges.values().all(|&n| n == 2));
        assert_eq!(
            m.positions.len() as i64 - edges.len() as i64 + m.indices.len() as i64,
            2
        );
    }
}
