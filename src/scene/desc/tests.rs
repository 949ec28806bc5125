//! Unit tests of scene files: errors that name their line, assets placed and overridden, lights,
//! moving assets, the lens and CSG objects.

use super::*;
use crate::sample::SamplerKind;
use crate::scene::MaterialLayers;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn unknown_key_names_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "s.toml",
        "[render]\nspp = 4\n\n[camera]\nposition = [0, 0, 5]\nlook_at = [0, 0, 0]\nfvo = 30\n",
    );
    let e = load(&p).unwrap_err().to_string();
    assert!(
        e.contains("s.toml") && e.contains("line 7") && e.contains("fvo"),
        "{e}"
    );
}

#[test]
fn wrong_type_names_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(dir.path(), "s.toml", "[render]\nwidth = \"wide\"\n");
    let e = load(&p).unwrap_err().to_string();
    assert!(e.contains("line 2"), "{e}");
}

#[test]
fn unknown_material_names_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    write(dir.path(), "t.obj", obj);
    let p = write(
        dir.path(),
        "s.toml",
        "[[material]]\nname = \"red\"\nbase_color = [1, 0, 0]\n\n[[asset]]\npath = \"t.obj\"\nmaterial = \"blue\"\n",
    );
    let e = load(&p).unwrap_err().to_string();
    assert!(e.contains("line 7") && e.contains("blue"), "{e}");
}

#[test]
fn assets_are_placed_and_overridden() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    let p = write(
        dir.path(),
        "s.toml",
        r#"
[render]
spp = 8
sampler = "stratified"

[[material]]
name = "gold"
base_color = [1, 0.8, 0.3]
metallic = 1
roughness = 0.2

[[asset]]
path = "t.obj"
transform = { translate = [10, 0, 0] }

[[asset]]
path = "t.obj"
material = "gold"
transform = { scale = 2, rotate_z = 90 }

[[light]]
type = "point"
position = [0, 0, 3]
intensity = 5

[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
fov = 30
"#,
    );
    let s = load(&p).unwrap();
    assert_eq!(s.instances.len(), 2);
    assert_eq!(s.settings.spp, Some(8));
    assert_eq!(s.settings.sampler, Some(SamplerKind::Stratified));
    let t0 = s.world_triangle(0, 0);
    assert!((t0[1] - Vec3::new(11.0, 0.0, 0.0)).length() < 1e-5);
    // Scaled by 2, then turned 90 degrees about z: (1,0,0) -> (0,2,0).
    let t1 = s.world_triangle(1, 0);
    assert!((t1[1] - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-5, "{t1:?}");
    assert_eq!(s.material_of(1).name, "gold");
    assert_ne!(s.material_of(0).name, "gold");
    assert_eq!(s.lights.len(), 1);
    assert_eq!(s.cameras[0].name, "scene file");
}

#[test]
fn area_lights_face_where_they_are_told() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        dir.path(),
        "s.toml",
        r#"
[[light]]
type = "rect"
center = [0, 2, 0]
size = [2, 1]
look_at = [0, 0, 0]
strength = 3

[[light]]
type = "disk"
center = [1, 1, 1]
radius = 0.5
normal = [0, 0, 1]
strength = 1

[[light]]
type = "sphere"
center = [0, 1, 0]
radius = 0.1
color = [1, 0.5, 0.25]
strength = 4
"#,
    );
    let s = load(&p).unwrap();
    match s.lights[0] {
        super::super::Light::Rect(super::super::RectLight {
            corner,
            edge_u,
            edge_v,
            radiance,
        }) => {
            let n = edge_u.cross(edge_v).normalize();
            assert!((n - Vec3::NEG_Y).length() < 1e-6, "{n}");
            assert!((corner + 0.5 * (edge_u + edge_v) - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6);
            assert!((edge_u.length() * edge_v.length() - 2.0).abs() < 1e-5);
            assert_eq!(radiance, Vec3::splat(3.0));
        }
        ref l => panic!("{l:?}"),
    }
    assert!(matches!(s.lights[1], super::super::Light::Disk(d) if d.normal == Vec3::Z));
    assert!(
        matches!(s.lights[2], super::super::Light::Sphere(l) if l.radiance == Vec3::new(4.0, 2.0, 1.0))
    );
    let bad = write(
        dir.path(),
        "b.toml",
        "[[light]]\ntype = \"disk\"\ncenter = [0, 0, 0]\nradius = 1\nstrength = 1\n",
    );
    let e = load(&bad).unwrap_err().to_string();
    assert!(e.contains("line 1") && e.contains("normal"), "{e}");
}

#[test]
fn moving_assets_lens_and_csg_objects() {
    let dir = tempfile::tempdir().unwrap();
    // A closed tetrahedron, to be cut by a box.
    write(
        dir.path(),
        "tet.obj",
        "o tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    );
    write(
        dir.path(),
        "t.obj",
        "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let p = write(
        dir.path(),
        "s.toml",
        r#"
[[material]]
name = "red"
base_color = [1, 0, 0]

[[asset]]
path = "t.obj"
transform = { translate = [0, 0, 0] }
transform_end = { translate = [2, 0, 0] }

[[asset]]
path = "tet.obj"

[[object]]
csg = { difference = [ { mesh = "tet" }, { box = { min = [0.5, -1, -1], max = [2, 2, 2] } } ] }
material = "red"

[[object]]
csg = { sphere = { center = [0, 0, 0], radius = 0.5 } }
transform = { translate = [0, 3, 0] }
transform_end = { translate = [1, 3, 0], rotate_y = 90 }

[camera]
position = [0, 0, 5]
look_at = [0, 0, 0]
aperture = 0.1
shutter = [0, 0.5]
"#,
    );
    let s = load(&p).unwrap();
    // The moving triangle: at shutter close it has moved by (2, 0, 0).
    let m = s.instances[0].motion.as_ref().expect("the asset moves");
    let end = m.at(1.0).transform_point3(Vec3::ZERO);
    assert!((end - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-4, "{end}");
    // The tetrahedron became a CSG operand: its own instance left the scene.
    assert_eq!(s.instances.len(), 1);
    assert_eq!(s.csg.len(), 2);
    // The moving sphere turns as it goes: more than two time steps; the cut tetrahedron stays.
    assert!(!s.csg[0].moves() && s.csg[1].moves() && s.csg[1].time_steps() > 2);
    let moved = crate::geometry::Ray::new(Vec3::new(1.0, 3.0, 5.0), -Vec3::Z).with_time(1.0);
    assert!(s.csg[1].intersect(&moved).is_some());
    assert!(s.csg[1].intersect(&moved.with_time(0.0)).is_none());
    let lens = s.cameras[0].lens.expect("aperture gives a lens");
    assert!((lens.radius - 0.1).abs() < 1e-6 && (lens.focus_distance - 5.0).abs() < 1e-5);
    // A ray along x at y = z = 0.1 enters the cut tetrahedron at x = 0 and leaves at the cut.
    let ray = crate::geometry::Ray::new(Vec3::new(-1.0, 0.1, 0.1), Vec3::X);
    let (t, _) = s.csg[0].intersect(&ray).expect("hits the cut tetrahedron");
    assert!((t - 1.0).abs() < 1e-4, "{t}");
    let back = crate::geometry::Ray::new(Vec3::new(3.0, 0.1, 0.1), -Vec3::X);
    let (t, _) = s.csg[0].intersect(&back).expect("hits the cut face");
    assert!((t - 2.5).abs() < 1e-4, "{t}");
    let bad = write(
        dir.path(),
        "b.toml",
        "[[object]]\ncsg = { mesh = \"nothing\" }\n",
    );
    let e = load(&bad).unwrap_err().to_string();
    assert!(e.contains("line 1") && e.contains("nothing"), "{e}");
}

/// The materials a scene file defines (with no assets), by name.
fn file_materials(text: &str) -> Result<Vec<Material>, String> {
    let s = load_str(Path::new("m.toml"), text).map_err(|e| e.to_string())?;
    Ok(s.materials)
}

#[test]
fn material_layers_take_their_gltf_meanings() {
    let m = file_materials(
        r#"
[[material]]
name = "all"
specular_color = [0.9, 0.8, 0.7]
dispersion = 0.25
thickness = 1
clearcoat = { factor = 0.6, roughness = 0.2 }
sheen = { color = [0.5, 0.4, 0.3], roughness = 0.7 }
anisotropy = { strength = 0.8, rotation = 90 }
iridescence = { factor = 0.9, ior = 1.4, thickness = 550 }
diffuse_transmission = { factor = 0.3, color = [1, 0.5, 0.25] }

[[material]]
name = "bare"
unlit = true
[material.clearcoat]
[material.sheen]
[material.iridescence]
[material.diffuse_transmission]

[[material]]
name = "off"
clearcoat = { factor = 0 }
sheen = { color = [0, 0, 0] }
anisotropy = { strength = 0 }
iridescence = { factor = 0 }
diffuse_transmission = { factor = 0 }
"#,
    )
    .unwrap();
    let by = |n: &str| m.iter().find(|m| m.name == n).unwrap().clone();
    let all = by("all");
    let l = &all.layers;
    assert_eq!(l.specular_color, Vec3::new(0.9, 0.8, 0.7));
    assert_eq!(l.dispersion, 0.25);
    let c = l.clearcoat.unwrap();
    assert_eq!((c.factor, c.roughness, c.normal_scale), (0.6, 0.2, 1.0));
    let s = l.sheen.unwrap();
    assert_eq!((s.color, s.roughness), (Vec3::new(0.5, 0.4, 0.3), 0.7));
    let a = l.anisotropy.unwrap();
    assert_eq!(a.strength, 0.8);
    assert!((a.rotation - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    let i = l.iridescence.unwrap();
    assert_eq!((i.factor, i.ior, i.thickness_max), (0.9, 1.4, 550.0));
    let d = l.diffuse_transmission.unwrap();
    assert_eq!((d.factor, d.color), (0.3, Vec3::new(1.0, 0.5, 0.25)));
    assert!(!all.unlit);

    // A bare table is a visible layer: a full smooth coat, a white sheen, the extensions' film.
    let bare = by("bare");
    assert!(bare.unlit);
    let l = &bare.layers;
    let c = l.clearcoat.unwrap();
    assert_eq!((c.factor, c.roughness), (1.0, 0.0));
    assert_eq!(l.sheen.unwrap().color, Vec3::ONE);
    let i = l.iridescence.unwrap();
    assert_eq!(
        (i.factor, i.ior, i.thickness_min, i.thickness_max),
        (1.0, 1.3, 400.0, 400.0)
    );
    assert_eq!(l.diffuse_transmission.unwrap().factor, 1.0);
    assert_eq!(l.specular_color, Vec3::ONE);

    // At strength 0 a layer is off, as a glTF extension's is.
    assert_eq!(by("off").layers, MaterialLayers::default());
}

#[test]
fn material_layers_out_of_range_are_named() {
    for (table, field) in [
        ("clearcoat = { factor = 1.5 }", "clearcoat.factor"),
        ("clearcoat = { roughness = -0.1 }", "clearcoat.roughness"),
        ("sheen = { color = [2, 0, 0] }", "sheen.color"),
        ("sheen = { roughness = 3 }", "sheen.roughness"),
        ("anisotropy = { strength = 2 }", "anisotropy.strength"),
        (
            "anisotropy = { strength = 1, rotation = nan }",
            "anisotropy.rotation",
        ),
        ("iridescence = { ior = 0.5 }", "iridescence.ior"),
        ("iridescence = { thickness = -1 }", "iridescence.thickness"),
        (
            "diffuse_transmission = { color = [0, -1, 0] }",
            "diffuse_transmission.color",
        ),
        (
            "diffuse_transmission = { factor = 1.01 }",
            "diffuse_transmission.factor",
        ),
        ("specular_color = [1, 1, 1.5]", "specular_color"),
        ("dispersion = -1", "dispersion"),
        ("dispersion = inf", "dispersion"),
    ] {
        let text = format!("[[material]]\nname = \"m\"\n{table}\n");
        let e = file_materials(&text).unwrap_err();
        assert!(
            e.contains("m.toml") && e.contains("material 'm'") && e.contains(field),
            "{table}: {e}"
        );
    }
    let e =
        file_materials("[[material]]\nname = \"m\"\nsheen = { colour = [1, 1, 1] }\n").unwrap_err();
    assert!(e.contains("line 3") && e.contains("colour"), "{e}");
}

#[test]
fn an_asset_named_twice_is_read_once_and_warns_once() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "t.obj",
        "mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let p = write(
        dir.path(),
        "s.toml",
        "[[asset]]\npath = \"t.obj\"\n\n[[asset]]\npath = \"t.obj\"\ntransform = { translate = [5, 0, 0] }\n",
    );
    let s = load(&p).unwrap();
    assert_eq!(s.instances.len(), 2);
    assert!((s.world_triangle(1, 0)[0] - Vec3::new(5.0, 0.0, 0.0)).length() < 1e-6);
    let warned: Vec<_> = s.warnings.iter().filter(|w| w.contains("t.obj")).collect();
    assert_eq!(warned.len(), 1, "{:?}", s.warnings);
}
