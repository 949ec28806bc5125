//! What glTF and OBJ files may use beyond the basics, checked on renders and loads: quantized attributes against their
//! float originals, vertex colours, texture coordinate sets other than 0.

mod common;

use std::path::Path;
use std::sync::Arc;

use glint::film::Image;
use glint::render::RenderSettings;
use glint::scene::{Camera, Scene};

fn settings() -> RenderSettings {
    RenderSettings {
        width: 80,
        height: 60,
        spp: 8,
        max_depth: 3,
        seed: 7,
        ..Default::default()
    }
}

/// Mean absolute difference over the mean of `a`.
fn rel_mad(a: &Image, b: &Image) -> f64 {
    a.mean_abs_diff(b) / a.mean_rgb().max(1e-9)
}

/// One image per render backend.
fn renders(scene: &Arc<Scene>, camera: &Camera) -> Vec<Image> {
    common::render_backends()
        .into_iter()
        .map(|b| {
            let img = common::render_with(scene, camera, b, &settings());
            assert!(!img.has_non_finite(), "{b}: NaN/Inf pixel");
            img
        })
        .collect()
}

#[test]
fn quantized_variants_render_like_their_originals() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let own = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let pairs = [
        (
            shared.join("gltf/Duck/glTF-Quantized/Duck.gltf"),
            shared.join("gltf/Duck/glTF-Binary/Duck.glb"),
        ),
        (
            shared.join("gltf/AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf"),
            own.join("dequantized/AnimatedMorphCube.gltf"),
        ),
    ];
    let s = settings();
    for (quantized, original) in pairs {
        // Both through the original's camera, so that framing differences cannot hide.
        let (orig, camera) = common::load_for_render(&original, s.width, s.height);
        let (quant, _) = common::load_for_render(&quantized, s.width, s.height);
        for (b, (a, q)) in common::render_backends().into_iter().zip(
            renders(&orig, &camera)
                .iter()
                .zip(&renders(&quant, &camera)),
        ) {
            let d = rel_mad(a, q);
            eprintln!("{}: {b}: relative MAD {d:.2e}", quantized.display());
            assert!(a.mean_rgb() > 1e-3, "{}: black render", original.display());
            assert!(d <= 0.005, "{}: {b}: relative MAD {d}", quantized.display());
        }
    }
}

/// The file rendered as it is and rendered after `edit`; both images, per backend.
fn with_and_after(path: &Path, edit: impl Fn(&mut Scene)) -> Vec<(Image, Image)> {
    let s = settings();
    let (scene, camera) = common::load_for_render(path, s.width, s.height);
    let mut edited = (*scene).clone();
    edit(&mut edited);
    renders(&scene, &camera)
        .into_iter()
        .zip(renders(&Arc::new(edited), &camera))
        .collect()
}

/// A render where TEXCOORD_1 was swapped into set 0 and the textures that read set 1 read set 0
/// instead is the known answer: it must equal the render of the file as it is, and differ from a
/// render that samples everything with set 0 (what glint did before), so the test can tell.
#[test]
fn textures_read_their_own_coordinate_sets() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    for f in [
        "gltf/MultiUVTest/glTF-Binary/MultiUVTest.glb",
        "gltf/TextureTransformMultiTest/glTF-Binary/TextureTransformMultiTest.glb",
    ] {
        let path = shared.join(f);
        let scene = Scene::load(&path).unwrap();
        let reads_set_1 = scene
            .materials
            .iter()
            .flat_map(|m| [m.base_color_tex, m.normal_tex, m.emissive_tex])
            .flatten()
            .any(|t| t.tex_coord == 1);
        assert!(reads_set_1, "{f}: no texture reads TEXCOORD_1");
        let swapped = with_and_after(&path, |s| {
            // A mesh without set 1 gets a copy of set 0, so either set reads the same there.
            for m in &mut s.meshes {
                if m.uv_sets.is_empty() {
                    m.uv_sets.push(Vec::new());
                }
                if m.uv_sets[0].is_empty() {
                    m.uv_sets[0] = m.uvs.clone();
                }
                std::mem::swap(&mut m.uvs, &mut m.uv_sets[0]);
            }
            for m in &mut s.materials {
                for t in m.textures_mut() {
                    t.tex_coord = if t.tex_coord == 1 { 0 } else { 1 };
                }
            }
        });
        let naive = with_and_after(&path, |s| {
            for m in &mut s.materials {
                for t in m.textures_mut() {
                    t.tex_coord = 0;
                }
            }
        });
        for ((a, b), (_, c)) in swapped.iter().zip(&naive) {
            let same = rel_mad(a, b);
            let set0 = rel_mad(a, c);
            eprintln!("{f}: swapped sets {same:.2e}, everything on set 0 {set0:.2e}");
            assert!(
                same < 1e-4,
                "{f}: swapping the sets changed the render by {same}"
            );
            assert!(set0 > 1e-3, "{f}: set 1 makes no difference ({set0})");
        }
    }
}

/// Vertex colours reach the image: every pixel of the render with colours is the render without
/// them scaled per channel by no more than the brightest colour, and the colours change it.
#[test]
fn vertex_colours_show() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    for f in [
        "gltf/BoxVertexColors/glTF-Binary/BoxVertexColors.glb",
        "gltf/VertexColorTest/glTF-Binary/VertexColorTest.glb",
    ] {
        let path = shared.join(f);
        let scene = Scene::load(&path).unwrap();
        assert!(
            scene.meshes.iter().any(|m| !m.colors.is_empty()),
            "{f}: no COLOR_0 read"
        );
        for (with, without) in with_and_after(&path, |s| {
            for m in &mut s.meshes {
                m.colors.clear();
            }
        }) {
            let d = rel_mad(&without, &with);
            eprintln!("{f}: colours change the render by {d:.3}");
            assert!(d > 0.05, "{f}: vertex colours make no difference ({d})");
        }
    }
}

/// SimpleInstancing: 125 instances of one mesh through EXT_mesh_gpu_instancing, each its own
/// placement, and every backend shows them.
#[test]
fn gpu_instancing_places_every_instance() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("gltf/SimpleInstancing/glTF-Binary/SimpleInstancing.glb");
    let scene = Scene::load(&path).unwrap();
    assert_eq!(scene.instances.len(), 125);
    let mut places: Vec<[i64; 3]> = scene
        .instances
        .iter()
        .map(|i| {
            (i.to_world.w_axis.truncate() * 1000.0)
                .round()
                .as_i64vec3()
                .to_array()
        })
        .collect();
    places.sort();
    places.dedup();
    assert_eq!(places.len(), 125, "instances share a place");
    // The other 124 instances cover much of the frame the first leaves to the background.
    for (all, one) in with_and_after(&path, |s| s.instances.truncate(1)) {
        let changed = all
            .pixels
            .iter()
            .zip(&one.pixels)
            .filter(|(a, o)| (**a - **o).abs().max_element() > 1e-3)
            .count();
        let share = changed as f64 / all.pixels.len() as f64;
        eprintln!("SimpleInstancing: {share:.3} of the pixels change with every instance");
        assert!(share > 0.2, "{share}");
    }
}

/// A glTF file with `n` instances (EXT_mesh_gpu_instancing translations on a grid) of a tetrahedron.
fn instanced_file(dir: &Path, n: usize) -> std::path::PathBuf {
    let pos: [[f32; 3]; 4] = [[0., 0., 0.], [0.5, 0., 0.], [0., 0.5, 0.], [0., 0., 0.5]];
    let idx: [u16; 12] = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
    let side = (n as f64).cbrt().ceil() as usize;
    let mut bin: Vec<u8> = pos.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
    bin.extend(idx.iter().flat_map(|i| i.to_le_bytes()));
    let t_off = bin.len();
    for i in 0..n {
        let (x, y, z) = (i % side, i / side % side, i / (side * side));
        for c in [x, y, z] {
            bin.extend((c as f32).to_le_bytes());
        }
    }
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "extensionsUsed": ["EXT_mesh_gpu_instancing"],
  "buffers": [{{"byteLength": {len}, "uri": "i.bin"}}],
  "bufferViews": [{{"buffer": 0, "byteLength": 48}}, {{"buffer": 0, "byteOffset": 48, "byteLength": 24}},
    {{"buffer": 0, "byteOffset": {t_off}, "byteLength": {tl}}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"}},
    {{"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}},
    {{"bufferView": 2, "componentType": 5126, "count": {n}, "type": "VEC3"}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "nodes": [{{"mesh": 0, "extensions": {{"EXT_mesh_gpu_instancing": {{"attributes": {{"TRANSLATION": 2}}}}}}}}],
  "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        len = bin.len(),
        tl = n * 12,
    );
    std::fs::write(dir.join("i.bin"), bin).unwrap();
    let p = dir.join("instances.gltf");
    std::fs::write(&p, json).unwrap();
    p
}

/// 100k instances of a small mesh load and build quickly on every backend (the target is under a
/// second for load + build; the bound here is loose, for busy test machines).
#[test]
fn hundred_thousand_instances_load_and_build() {
    let dir = tempfile::tempdir().unwrap();
    let path = instanced_file(dir.path(), 100_000);
    let t0 = std::time::Instant::now();
    let scene = Arc::new(Scene::load(&path).unwrap());
    let load = t0.elapsed();
    assert_eq!(scene.instances.len(), 100_000);
    assert_eq!(scene.meshes.len(), 1);
    for b in glint::accel::Backend::all_available() {
        let t1 = std::time::Instant::now();
        let _accel = glint::accel::build(scene.clone(), b).unwrap();
        let build = t1.elapsed();
        eprintln!(
            "100k instances: load {:.3} s, {b} build {:.3} s, total {:.3} s",
            load.as_secs_f64(),
            build.as_secs_f64(),
            (load + build).as_secs_f64()
        );
        assert!((load + build).as_secs_f64() < 20.0);
    }
}

/// An asymmetric OBJ (a tall post on a wide slab, Y up), its vertices mapped by `f`.
fn post_and_slab(f: impl Fn([f32; 3]) -> [f32; 3]) -> String {
    use glam::Vec3;
    use glint::scene::generate::box_mesh;
    let boxes = [
        box_mesh(Vec3::new(-1.0, 0.0, -0.6), Vec3::new(1.0, 0.2, 0.6)),
        box_mesh(Vec3::new(0.3, 0.2, -0.15), Vec3::new(0.6, 1.5, 0.15)),
    ];
    let mut obj = String::new();
    let mut first = 1;
    for m in &boxes {
        for p in &m.positions {
            let [x, y, z] = f(p.to_array());
            obj += &format!("v {x} {y} {z}\n");
        }
        for t in &m.indices {
            let [a, b, c] = t.map(|k| k + first);
            obj += &format!("f {a} {b} {c}\n");
        }
        first += m.positions.len() as u32;
    }
    obj
}

#[test]
fn a_z_up_file_turned_up_renders_as_its_y_up_twin() {
    use glint::render::job::Setup;
    use glint::scene::UpAxis;
    let dir = tempfile::tempdir().unwrap();
    let y_up = dir.path().join("y.obj");
    let z_up = dir.path().join("z.obj");
    std::fs::write(&y_up, post_and_slab(|p| p)).unwrap();
    // Z-up coordinates of the same model: (x, y, z) -> (x, -z, y).
    std::fs::write(&z_up, post_and_slab(|[x, y, z]| [x, -z, y])).unwrap();
    let render = |path: &Path, up: UpAxis| {
        let mut opts = common::render_options(80, 60);
        opts.up_axis = up;
        let setup = Setup::new(Scene::load(path).unwrap(), &opts).unwrap();
        let scene = Arc::new(setup.scene);
        common::render_with(
            &scene,
            &setup.camera,
            glint::accel::Backend::Bvh,
            &settings(),
        )
    };
    let reference = render(&y_up, UpAxis::Y);
    let turned = render(&z_up, UpAxis::Z);
    let unturned = render(&z_up, UpAxis::Y);
    let (d_turned, d_unturned) = (rel_mad(&reference, &turned), rel_mad(&reference, &unturned));
    assert!(d_turned < 1e-3, "turned Z-up file differs by {d_turned}");
    assert!(d_unturned > 0.05, "unturned differs by only {d_unturned}");
}

#[test]
fn blender_pbr_obj_reads_as_blender_reads_it() {
    // Blender 5.0.1's importer gives these Principled values for the file its exporter wrote.
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/obj_pbr/blender_pbr.obj");
    let s = Scene::load(&path).unwrap();
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    let by_name = |n: &str| s.materials.iter().find(|m| m.name == n).unwrap();
    let c = by_name("coated");
    assert_eq!((c.roughness, c.metallic, c.specular), (0.3, 1.0, 0.5));
    assert_eq!(c.layers.sheen.unwrap().color, glam::Vec3::splat(0.2));
    let coat = c.layers.clearcoat.unwrap();
    assert_eq!((coat.factor, coat.roughness), (0.5, 0.1));
    let aniso = c.layers.anisotropy.unwrap();
    assert_eq!(aniso.strength, 0.4);
    assert!((aniso.rotation - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    let t = by_name("textured");
    assert_eq!((t.roughness, t.metallic, t.specular), (1.0, 0.0, 1.0));
    let tex = &s.textures[t.metallic_roughness_tex.unwrap().texture as usize];
    assert_eq!(tex.pixels, vec![[0, 51, 255, 255], [0, 204, 255, 255]]);
    assert!(t.layers.clearcoat.is_none() && t.layers.sheen.is_none());
}

#[test]
fn multiple_scenes_loads_each_scene() {
    use glint::scene::{LoadOptions, SceneChoice};
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("gltf/MultipleScenes/glTF/MultipleScenes.gltf");
    let triangles = |i: usize| {
        let opts = LoadOptions {
            scene: SceneChoice::Index(i),
            ..Default::default()
        };
        Scene::load_with(&path, &opts).unwrap().triangle_count()
    };
    // Scene 0 is a triangle, scene 1 a square (the model's README).
    assert_eq!((triangles(0), triangles(1)), (1, 2));
    assert!(Scene::load_with(
        &path,
        &LoadOptions {
            scene: SceneChoice::Index(2),
            ..Default::default()
        }
    )
    .is_err());
}
