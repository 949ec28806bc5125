//! Unit tests of the glTF loader on small documents written to a temp dir (data-URI buffers), and
//! a load of every shared asset with its known counts.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};

use super::uv_transform;
use crate::scene::{
    AlphaMode, DirectionalLight, Light, PointLight, Projection, Scene, SpotLight, TexRef,
    TextureFilter, Wrap,
};

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Little-endian bytes of positions then (optionally) u16 indices, padded to 4.
fn geometry(pos: &[[f32; 3]], idx: &[u16]) -> Vec<u8> {
    let mut b: Vec<u8> = pos.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
    b.extend(idx.iter().flat_map(|i| i.to_le_bytes()));
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    b
}

/// A document over `data` (its one buffer, as a data URI) whose other top-level members are
/// `members` (JSON object members, without the braces), written to `dir` as `name`.
fn write_doc(dir: &tempfile::TempDir, name: &str, data: &[u8], members: &str) -> PathBuf {
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}},
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{b64}"}}],
  {members}
}}"#,
        len = data.len(),
        b64 = base64(data),
    );
    let p = dir.path().join(name);
    std::fs::write(&p, json).unwrap();
    p
}

/// A document whose mesh 0 is one primitive over `pos` (and `idx` when not empty), plus `extra`
/// top-level members (nodes, scenes, ...), written to a temp dir.
fn write(dir: &tempfile::TempDir, pos: &[[f32; 3]], idx: &[u16], extra: &str) -> PathBuf {
    let data = geometry(pos, idx);
    let pos_len = pos.len() * 12;
    let indices = if idx.is_empty() {
        String::new()
    } else {
        r#", "indices": 1"#.to_string()
    };
    let members = format!(
        r#""bufferViews": [
{{"buffer": 0, "byteOffset": 0, "byteLength": {pos_len}}},
{{"buffer": 0, "byteOffset": {pos_len}, "byteLength": {idx_len}}}
  ],
  "accessors": [
{{"bufferView": 0, "componentType": 5126, "count": {np}, "type": "VEC3"}},
{{"bufferView": 1, "componentType": 5123, "count": {ni}, "type": "SCALAR"}}
  ],
  "meshes": [{{"name": "tri", "primitives": [{{"attributes": {{"POSITION": 0}}{indices}}}]}}],
  {extra}"#,
        idx_len = (idx.len() * 2).max(2),
        np = pos.len(),
        ni = idx.len().max(1),
    );
    write_doc(dir, "t.gltf", &data, &members)
}

/// `write` into a fresh temp dir, then loaded (the scene holds no reference to the files).
fn load(pos: &[[f32; 3]], idx: &[u16], extra: &str) -> Result<Scene, crate::scene::LoadError> {
    let dir = tempfile::tempdir().unwrap();
    Scene::load(&write(&dir, pos, idx, extra))
}

const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

#[test]
fn morph_target_weights_are_animated_and_posed() {
    // A triangle, one target lifting it by z = 1, weights keyed 0 -> 1 over a second.
    let floats: Vec<f32> = TRI
        .iter()
        .flatten()
        .copied()
        .chain([0.0, 0.0, 1.0].repeat(3))
        .chain([0.0, 1.0, 0.0, 1.0])
        .collect();
    let data: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let members = format!(
        r#""bufferViews": [{{"buffer": 0, "byteLength": {len}}}],
  "accessors": [
{{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
{{"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"}},
{{"bufferView": 0, "byteOffset": 72, "componentType": 5126, "count": 2, "type": "SCALAR"}},
{{"bufferView": 0, "byteOffset": 80, "componentType": 5126, "count": 2, "type": "SCALAR"}}
  ],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "targets": [{{"POSITION": 1}}]}}],
          "weights": [0.25]}}],
  "nodes": [{{"mesh": 0}}],
  "scenes": [{{"nodes": [0]}}],
  "animations": [{{"channels": [{{"sampler": 0, "target": {{"node": 0, "path": "weights"}}}}],
               "samplers": [{{"input": 2, "output": 3}}]}}]"#,
        len = data.len(),
    );
    let dir = tempfile::tempdir().unwrap();
    let p = write_doc(&dir, "m.gltf", &data, &members);
    let scene = Scene::load(&p).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let z_at = |t: f32| {
        let mut s = scene.clone();
        crate::scene::animation::pose(&mut s, t, [0.0, 0.0]);
        s.meshes[0]
            .positions
            .iter()
            .map(|p| p.z)
            .collect::<Vec<_>>()
    };
    assert_eq!(z_at(0.5), vec![0.5; 3]);
    assert_eq!(z_at(7.0), vec![1.0; 3]);
    // Unposed, the mesh is the file's base shape.
    assert!(scene.meshes[0].positions.iter().all(|p| p.z == 0.0));
    let a = scene.animation.as_ref().unwrap();
    assert_eq!(a.morphs[0].default_weights, vec![0.25]);
}

#[test]
fn one_mesh_two_nodes_is_one_mesh_two_instances() {
    let s = load(
        &TRI,
        &[0, 1, 2],
        r#""nodes": [{"mesh": 0, "translation": [5, 0, 0]}, {"mesh": 0}],
           "scenes": [{"nodes": [0, 1]}], "scene": 0"#,
    )
    .unwrap();
    assert_eq!(s.meshes.len(), 1);
    assert_eq!(s.instances.len(), 2);
    assert_eq!(s.stats.triangles, 2);
    assert_eq!(s.stats.nodes, 2);
    assert_eq!(s.stats.meshes, 1);
    assert_eq!(s.stats.primitives, 1);
    assert_eq!(
        s.instances[0].to_world.w_axis.truncate(),
        Vec3::new(5.0, 0.0, 0.0)
    );
    assert!(s.instances[1].is_identity());
    // No material in the file: one default material, exactly the spec default.
    assert_eq!(s.materials.len(), 1);
    assert_eq!(s.materials[0].metallic, 1.0);
    assert_eq!(s.materials[0].roughness, 1.0);
}

#[test]
fn hierarchy_composes_parent_then_child() {
    let s = load(
        &TRI,
        &[0, 1, 2],
        r#""nodes": [{"translation": [1, 0, 0], "scale": [2, 2, 2], "children": [1]},
                     {"mesh": 0, "translation": [0, 1, 0]}],
           "scenes": [{"nodes": [0]}]"#,
    )
    .unwrap();
    assert_eq!(s.instances.len(), 1);
    let m = s.instances[0].to_world;
    assert!((m.transform_point3(Vec3::ZERO) - Vec3::new(1.0, 2.0, 0.0)).length() < 1e-6);
    assert!((m.transform_point3(Vec3::X) - Vec3::new(3.0, 2.0, 0.0)).length() < 1e-6);
}

#[test]
fn no_scenes_uses_root_nodes() {
    let s = load(
        &TRI,
        &[0, 1, 2],
        r#""nodes": [{"children": [1]}, {"mesh": 0}, {"mesh": 0}]"#,
    )
    .unwrap();
    assert_eq!(s.instances.len(), 2);
}

#[test]
fn non_indexed_primitive_and_computed_normals() {
    let quad = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let s = load(
        &quad,
        &[],
        r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
    )
    .unwrap();
    assert_eq!(s.meshes[0].indices.len(), 2);
    assert_eq!(s.stats.triangles, 2);
    assert_eq!(s.meshes[0].normals.len(), 6);
    for n in &s.meshes[0].normals {
        assert!((*n - Vec3::Z).length() < 1e-6, "{n}");
    }
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
}

#[test]
fn nan_and_degenerate_triangles_are_dropped_with_one_warning() {
    let pos = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [f32::NAN, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [f32::INFINITY, 1.0, 1.0],
    ];
    // valid, NaN corner, repeated index, collinear (zero area), infinite corner
    let idx = [0, 1, 2, 0, 3, 1, 0, 0, 1, 0, 1, 4, 5, 1, 2];
    let s = load(
        &pos,
        &idx,
        r#""nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
    )
    .unwrap();
    assert_eq!(s.meshes[0].indices.len(), 1);
    assert!(s.meshes[0].positions.iter().all(|p| p.is_finite()));
    assert_eq!(s.meshes[0].positions.len(), 3);
    let w: Vec<_> = s
        .warnings
        .iter()
        .filter(|w| w.contains("degenerate"))
        .collect();
    assert_eq!(w.len(), 1, "{:?}", s.warnings);
    assert!(w[0].contains("dropped 4 degenerate triangles"), "{}", w[0]);
}

#[test]
fn unsupported_required_extension_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let e = load(
        &TRI,
        &[0, 1, 2],
        r#""nodes": [{"mesh": 0}],
           "extensionsUsed": ["EXT_lights_image_based", "KHR_materials_volume"],
           "extensionsRequired": ["KHR_materials_volume", "EXT_lights_image_based"]"#,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("requires unsupported extension EXT_lights_image_based"),
        "{e}"
    );
    assert!(e.contains("t.gltf"), "{e}");
    // A supported one that the gltf crate itself does not know is accepted.
    let p = write(
        &dir,
        &TRI,
        &[0, 1, 2],
        r#""nodes": [{"mesh": 0}], "extensionsUsed": ["KHR_materials_volume"],
           "extensionsRequired": ["KHR_materials_volume"]"#,
    );
    Scene::load(&p).unwrap();
}

#[test]
fn spot_and_point_lights() {
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let extra = format!(
        r#""extensionsUsed": ["KHR_lights_punctual"],
           "extensions": {{"KHR_lights_punctual": {{"lights": [
              {{"type": "spot", "color": [1, 0.5, 0.25], "intensity": 4,
                "spot": {{"innerConeAngle": 0.2, "outerConeAngle": 0.5}}}},
              {{"type": "point", "intensity": 2}},
              {{"type": "directional", "intensity": 3}}]}}}},
           "nodes": [
              {{"translation": [0, 5, 0], "rotation": [{nx}, 0, 0, {h}],
                "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}},
              {{"translation": [1, 2, 3], "extensions": {{"KHR_lights_punctual": {{"light": 1}}}}}},
              {{"extensions": {{"KHR_lights_punctual": {{"light": 2}}}}}}],
           "scenes": [{{"nodes": [0, 1, 2]}}]"#,
        nx = -h
    );
    let s = load(&TRI, &[0, 1, 2], &extra).unwrap();
    assert_eq!(s.lights.len(), 3);
    assert_eq!(s.stats.lights, 3);
    // The node turns -Z to -Y: compare the direction within rounding, the rest exactly.
    let Light::Spot(SpotLight {
        position,
        direction,
        ..
    }) = s.lights[0]
    else {
        panic!("expected a spot light, got {:?}", s.lights[0]);
    };
    assert!((direction - Vec3::NEG_Y).length() < 1e-5, "{direction}");
    assert_eq!(position, Vec3::new(0.0, 5.0, 0.0));
    let expected = Light::Spot(SpotLight {
        position,
        direction,
        intensity: Vec3::new(4.0, 2.0, 1.0),
        cos_inner: 0.2f32.cos(),
        cos_outer: 0.5f32.cos(),
    });
    assert_eq!(s.lights[0], expected);
    assert_eq!(
        s.lights[1],
        Light::Point(PointLight {
            position: Vec3::new(1.0, 2.0, 3.0),
            intensity: Vec3::splat(2.0)
        })
    );
    assert_eq!(
        s.lights[2],
        Light::Directional(DirectionalLight {
            direction: Vec3::NEG_Z,
            irradiance: Vec3::splat(3.0)
        })
    );
}

#[test]
fn cameras_in_document_order_without_scale() {
    let s = load(
        &TRI,
        &[0, 1, 2],
        r#""cameras": [
             {"name": "persp", "type": "perspective",
              "perspective": {"yfov": 0.7, "aspectRatio": 1.5, "znear": 0.1}},
             {"type": "orthographic",
              "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 10}}],
           "nodes": [{"name": "orthoNode", "camera": 1, "translation": [0, 0, 9]},
                     {"camera": 0, "translation": [1, 2, 3], "scale": [2, 2, 2]}],
           "scenes": [{"nodes": [0, 1]}]"#,
    )
    .unwrap();
    assert_eq!(s.cameras.len(), 2);
    assert_eq!(s.stats.cameras, 2);
    let c0 = &s.cameras[0];
    assert_eq!(c0.name, "persp");
    assert_eq!(
        c0.projection,
        Projection::Perspective {
            yfov: 0.7,
            aspect: Some(1.5)
        }
    );
    assert!((c0.position() - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
    assert!((c0.to_world.x_axis.truncate().length() - 1.0).abs() < 1e-6);
    let c1 = &s.cameras[1];
    assert_eq!(c1.name, "orthoNode");
    assert_eq!(
        c1.projection,
        Projection::Orthographic {
            xmag: 2.0,
            ymag: 1.0
        }
    );
}

/// A temp dir holding `tex.png`, a 2x1 image (opaque red, then half-transparent blue).
fn dir_with_tex_png() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let img = image::RgbaImage::from_raw(2, 1, vec![255, 0, 0, 255, 0, 0, 255, 128]).unwrap();
    img.save(dir.path().join("tex.png")).unwrap();
    dir
}

#[test]
fn sampler_filters_become_nearest_only_where_every_named_filter_is_nearest() {
    let dir = dir_with_tex_png();
    // (magFilter, minFilter) of each sampler, and the filter glint should take.
    let cases = [
        (Some(9728), None, TextureFilter::Nearest),
        (None, Some(9728), TextureFilter::Nearest),
        (Some(9728), Some(9986), TextureFilter::Nearest),
        (Some(9728), Some(9987), TextureFilter::Linear),
        (Some(9729), Some(9984), TextureFilter::Linear),
        (None, None, TextureFilter::Linear),
    ];
    let field =
        |name: &str, v: Option<u32>| v.map_or(String::new(), |v| format!(r#""{name}": {v}"#));
    let samplers: Vec<String> = cases
        .iter()
        .map(|(mag, min, _)| {
            let fields: Vec<String> = [field("magFilter", *mag), field("minFilter", *min)]
                .into_iter()
                .filter(|f| !f.is_empty())
                .collect();
            format!("{{{}}}", fields.join(", "))
        })
        .collect();
    let textures: Vec<String> = (0..cases.len())
        .map(|k| format!(r#"{{"source": 0, "sampler": {k}}}"#))
        .collect();
    let materials: Vec<String> = (0..cases.len())
        .map(|k| format!(r#"{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": {k}}}}}}}"#))
        .collect();
    let p = write(
        &dir,
        &TRI,
        &[0, 1, 2],
        &format!(
            r#""images": [{{"uri": "tex.png"}}], "samplers": [{}], "textures": [{}],
               "materials": [{}], "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}]"#,
            samplers.join(", "),
            textures.join(", "),
            materials.join(", ")
        ),
    );
    let s = Scene::load(&p).unwrap();
    for (k, (mag, min, want)) in cases.iter().enumerate() {
        let t = s.materials[k].base_color_tex.unwrap().texture;
        assert_eq!(
            s.textures[t as usize].filter, *want,
            "mag {mag:?}, min {min:?}"
        );
    }
}

#[test]
fn materials_textures_and_transform() {
    let dir = dir_with_tex_png();
    let p = write(
        &dir,
        &TRI,
        &[0, 1, 2],
        r#""images": [{"uri": "tex.png"}],
           "samplers": [{"wrapS": 33071, "wrapT": 33648}],
           "textures": [{"source": 0, "sampler": 0}],
           "extensionsUsed": ["KHR_texture_transform", "KHR_materials_emissive_strength",
                              "KHR_materials_transmission", "KHR_materials_ior"],
           "materials": [{"name": "m",
              "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                 "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
                    {"offset": [0.5, 0.25], "scale": [2, 3]}}},
                 "metallicFactor": 0.25, "roughnessFactor": 0.75,
                 "metallicRoughnessTexture": {"index": 0}},
              "normalTexture": {"index": 0, "scale": 0.5},
              "emissiveFactor": [1, 0.5, 0], "emissiveTexture": {"index": 0},
              "alphaMode": "MASK", "doubleSided": true,
              "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4},
                             "KHR_materials_transmission": {"transmissionFactor": 0.9},
                             "KHR_materials_ior": {"ior": 1.33}}}],
           "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]"#,
    );
    let s = Scene::load(&p).unwrap();
    // The helper's mesh names no material: the spec default is appended after the file's one.
    assert_eq!(s.materials.len(), 2);
    assert_eq!(s.meshes[0].material, 1);
    assert_eq!(s.materials[1].metallic, 1.0);
    let m = &s.materials[0];
    assert_eq!(m.name, "m");
    assert_eq!(m.metallic, 0.25);
    assert_eq!(m.roughness, 0.75);
    assert_eq!(m.emissive, Vec3::new(4.0, 2.0, 0.0));
    assert_eq!(m.alpha_mode, AlphaMode::Mask(0.5));
    assert!(m.double_sided);
    assert!((m.transmission - 0.9).abs() < 1e-6);
    assert!((m.ior - 1.33).abs() < 1e-6);
    assert_eq!(m.normal_scale, 0.5);
    // sRGB and linear variants of texture 0.
    assert_eq!(s.textures.len(), 2);
    let bc = m.base_color_tex.unwrap();
    let t = &s.textures[bc.texture as usize];
    assert!(t.srgb);
    assert_eq!((t.width, t.height), (2, 1));
    assert_eq!(t.pixels[1], [0, 0, 255, 128]);
    assert_eq!(t.wrap_s, Wrap::ClampToEdge);
    assert_eq!(t.wrap_t, Wrap::MirroredRepeat);
    assert_eq!(
        t.filter,
        TextureFilter::Linear,
        "a sampler naming no filter"
    );
    assert_eq!(bc.apply(Vec2::new(1.0, 1.0)), Vec2::new(2.5, 3.25));
    let mr = m.metallic_roughness_tex.unwrap();
    assert!(!s.textures[mr.texture as usize].srgb);
    assert_eq!(m.normal_tex.unwrap().texture, mr.texture);
    assert_eq!(m.emissive_tex.unwrap().texture, bc.texture);
    assert_eq!(s.stats.textures, 1);
}

#[test]
fn texture_transform_rotation_matches_spec() {
    let m = uv_transform([0.0, 0.0], std::f32::consts::FRAC_PI_2, [1.0, 1.0]);
    let t = TexRef {
        texture: 0,
        uv_transform: m,
        tex_coord: 0,
    };
    // The spec's rotation matrix [cos sin; -sin cos] takes (1, 0) to (0, -1).
    let r = t.apply(Vec2::new(1.0, 0.0));
    assert!((r - Vec2::new(0.0, -1.0)).length() < 1e-6, "{r}");
}

#[test]
fn accessor_past_its_buffer_is_an_error_naming_the_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(&dir, &TRI, &[0, 1, 2], r#""nodes": [{"mesh": 0}]"#);
    let text = std::fs::read_to_string(&p).unwrap().replace(
        r#""count": 3, "type": "VEC3""#,
        r#""count": 300, "type": "VEC3""#,
    );
    std::fs::write(&p, text).unwrap();
    let e = Scene::load(&p).unwrap_err().to_string();
    assert!(e.contains("mesh 0 ('tri'), primitive 0"), "{e}");
    assert!(e.contains("out of bounds"), "{e}");
}

#[test]
fn index_out_of_range_is_an_error() {
    let e = load(&TRI, &[0, 1, 7], r#""nodes": [{"mesh": 0}]"#)
        .unwrap_err()
        .to_string();
    assert!(e.contains("index 7 out of range"), "{e}");
}

#[test]
fn points_are_skipped_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(&dir, &TRI, &[0, 1, 2], r#""nodes": [{"mesh": 0}]"#);
    let text = std::fs::read_to_string(&p)
        .unwrap()
        .replace(r#""indices": 1"#, r#""indices": 1, "mode": 0"#);
    std::fs::write(&p, text).unwrap();
    let s = Scene::load(&p).unwrap();
    assert!(s.meshes.is_empty());
    assert!(s
        .warnings
        .iter()
        .any(|w| w.contains("mesh 0 ('tri'), primitive 0")));
}

#[test]
fn strips_and_fans_become_triangles() {
    let dir = tempfile::tempdir().unwrap();
    let quad = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    for (mode, idx) in [(5, [0u16, 1, 2, 3]), (6, [0, 1, 3, 2])] {
        let p = write(&dir, &quad, &idx, r#""nodes": [{"mesh": 0}]"#);
        let text = std::fs::read_to_string(&p).unwrap().replace(
            r#""indices": 1"#,
            &format!(r#""indices": 1, "mode": {mode}"#),
        );
        std::fs::write(&p, text).unwrap();
        let s = Scene::load(&p).unwrap();
        assert_eq!(s.meshes[0].indices.len(), 2);
        // Both triangles keep the same facing (+Z).
        for n in &s.meshes[0].normals {
            assert!((*n - Vec3::Z).length() < 1e-6, "mode {mode}: {n}");
        }
    }
}

/// Loads every asset of the shared set, when it is present, and checks known counts.
#[test]
fn shared_assets_load_with_sane_counts() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/assets");
    if !root.is_dir() {
        println!("shared assets not found at {}; skipped", root.display());
        return;
    }
    let mut files = Vec::new();
    let mut dirs = vec![root];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("glb" | "gltf" | "obj")
            ) {
                files.push(p);
            }
        }
    }
    files.sort();
    assert!(!files.is_empty());
    let expect: &[(&str, usize)] = &[
        ("Box.glb", 12),
        ("BoxTextured.glb", 12),
        ("Duck.glb", 4212),
        ("DamagedHelmet.glb", 15452),
        ("ToyCar.gltf", 108936),
        ("CornellBox-Original.obj", 36),
        ("TransmissionTest.glb", 128775),
        ("AttenuationTest.glb", 292),
        ("GlassVaseFlowers.glb", 14036),
        ("Cameras.gltf", 2),
        ("LightsPunctualLamp.gltf", 6000),
        ("spot.obj", 5856),
    ];
    for f in &files {
        let name = f.file_name().unwrap().to_str().unwrap();
        let s = match Scene::load(f) {
            Ok(s) => s,
            // Files that need an extension glint does not read yet are refused by design.
            Err(e) if e.to_string().contains("requires unsupported extension") => {
                println!("{name}: refused: {e}");
                continue;
            }
            Err(e) => panic!("{e}"),
        };
        println!(
            "{name}: {:?} meshes={} instances={} warnings={:?}",
            s.stats,
            s.meshes.len(),
            s.instances.len(),
            s.warnings
        );
        assert!(s.stats.triangles > 0, "{name}");
        assert_eq!(s.stats.triangles, s.triangle_count());
        for m in &s.meshes {
            assert!(m.positions.iter().all(|p| p.is_finite()), "{name}");
            assert!(m.normals.iter().all(|n| n.is_finite()), "{name}");
        }
        if let Some((_, n)) = expect.iter().find(|(f, _)| *f == name) {
            assert_eq!(s.stats.triangles, *n, "{name}");
        }
        match name {
            "stanford-bunny.obj" => {
                assert!(s.stats.triangles <= 69451 && s.stats.triangles > 69000)
            }
            "CornellBox-Original.obj" => {
                assert!(s.materials.iter().any(|m| m.is_emissive()));
            }
            "DamagedHelmet.glb" => {
                let m = &s.materials[0];
                assert!(m.base_color_tex.is_some() && m.normal_tex.is_some());
                assert!(m.emissive_tex.is_some() && m.metallic_roughness_tex.is_some());
            }
            "ToyCar.gltf" => assert_eq!(s.cameras.len(), 8),
            "Cameras.gltf" => assert_eq!(s.cameras.len(), 2),
            "LightsPunctualLamp.gltf" => assert_eq!(s.lights.len(), 5),
            "MetalRoughSpheresNoTextures.glb" => {
                // 1,040,409 in the file; each of the 98 sphere instances has 2 zero-area triangles.
                assert_eq!(s.stats.triangles, 1040409 - 98 * 2);
                assert_eq!(s.stats.materials, 98);
            }
            _ => {}
        }
    }
}

/// One triangle whose attributes are the given accessors (component type, type, normalized, bytes),
/// each in its own buffer view; `attrs` maps attribute names to accessor indices.
fn write_attrs(
    dir: &tempfile::TempDir,
    accessors: &[(u32, &str, bool, Vec<u8>)],
    attrs: &str,
    extra: &str,
) -> PathBuf {
    let mut data = Vec::new();
    let (mut views, mut accs) = (Vec::new(), Vec::new());
    for (i, (ct, ty, norm, bytes)) in accessors.iter().enumerate() {
        let width: usize = match *ty {
            "VEC2" => 2,
            "VEC3" => 3,
            _ => 4,
        } * match ct {
            5120 | 5121 => 1,
            5122 | 5123 => 2,
            _ => 4,
        };
        // Elements of quantized attributes are padded to 4 bytes (the spec's alignment rule).
        let stride = width.next_multiple_of(4);
        let mut padded = Vec::new();
        for e in bytes.chunks(width) {
            padded.extend_from_slice(e);
            padded.resize(padded.len().next_multiple_of(4), 0);
        }
        views.push(format!(
            r#"{{"buffer": 0, "byteOffset": {}, "byteLength": {}, "byteStride": {stride}}}"#,
            data.len(),
            padded.len()
        ));
        accs.push(format!(
            r#"{{"bufferView": {i}, "componentType": {ct}, "count": {}, "type": "{ty}", "normalized": {norm}}}"#,
            bytes.len() / width
        ));
        data.extend(padded);
    }
    let members = format!(
        r#""extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],
  "bufferViews": [{views}], "accessors": [{accs}],
  "meshes": [{{"primitives": [{{"attributes": {{{attrs}}}{material}}}]}}], "nodes": [{{"mesh": 0}}] {extra}"#,
        views = views.join(","),
        accs = accs.join(","),
        material = if extra.contains("\"materials\"") {
            r#", "material": 0"#
        } else {
            ""
        },
    );
    write_doc(dir, "q.gltf", &data, &members)
}

/// Integer components as little-endian bytes of component type `ct`.
fn ints(ct: u32, v: &[i32]) -> Vec<u8> {
    v.iter()
        .flat_map(|&x| match ct {
            5120 | 5121 => vec![x as u8],
            _ => (x as u16).to_le_bytes().to_vec(),
        })
        .collect()
}

#[test]
fn quantized_attributes_of_every_component_type() {
    let dir = tempfile::tempdir().unwrap();
    for ct in [5120u32, 5121, 5122, 5123] {
        let (max, signed) = match ct {
            5120 => (127.0, true),
            5121 => (255.0, false),
            5122 => (32767.0, true),
            _ => (65535.0, false),
        };
        // Plain integer positions, normalized normals (signed types only, as the extension allows)
        // and both kinds of UVs.
        let pos = [0, 0, 0, 3, 0, 0, 0, 5, 0];
        let nz = if signed { max as i32 } else { 0 };
        let mut accs = vec![
            (ct, "VEC3", false, ints(ct, &pos)),
            (ct, "VEC2", true, ints(ct, &[0, 0, 100, 7, 1, 100])),
            (ct, "VEC2", false, ints(ct, &[0, 0, 2, 1, 1, 9])),
        ];
        let mut attrs = r#""POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 2"#.to_string();
        if signed {
            accs.push((
                ct,
                "VEC3",
                true,
                ints(ct, &[0, 0, nz, 0, 0, nz, 0, 0, -nz - 1]),
            ));
            attrs += r#", "NORMAL": 3"#;
        }
        let p = write_attrs(&dir, &accs, &attrs, "");
        let s = Scene::load(&p).unwrap_or_else(|e| panic!("type {ct}: {e}"));
        let m = &s.meshes[0];
        assert_eq!(m.positions[1], Vec3::new(3.0, 0.0, 0.0), "type {ct}");
        assert_eq!(m.positions[2], Vec3::new(0.0, 5.0, 0.0), "type {ct}");
        assert_eq!(m.uvs[1], Vec2::new(100.0 / max, 7.0 / max), "type {ct}");
        assert_eq!(m.uv_sets[0][2], Vec2::new(1.0, 9.0), "type {ct}");
        if signed {
            // -max - 1 clamps to -1 (the spec's max(c / max, -1)).
            assert_eq!(m.normals[2], Vec3::new(0.0, 0.0, -1.0), "type {ct}");
            assert_eq!(m.normals[0], Vec3::Z, "type {ct}");
        }
    }
}

#[test]
fn vertex_colours_rgb_and_rgba_float_and_normalized() {
    let dir = tempfile::tempdir().unwrap();
    let pos: Vec<u8> = TRI.iter().flatten().flat_map(|f| f.to_le_bytes()).collect();
    let f32s = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    // (component type, accessor type, normalized, bytes) and the colour expected.
    type Case<'a> = ((u32, &'a str, bool, Vec<u8>), [f32; 4]);
    let cases: [Case; 3] = [
        (
            (5126, "VEC3", false, f32s(&[0.25, 0.5, 1.0].repeat(3))),
            [0.25, 0.5, 1.0, 1.0],
        ),
        (
            (5121, "VEC4", true, [51u8, 102, 255, 204].repeat(3)),
            [0.2, 0.4, 1.0, 0.8],
        ),
        (
            (
                5123,
                "VEC4",
                true,
                ints(5123, &[65535, 0, 13107, 32768].repeat(3)),
            ),
            [1.0, 0.0, 0.2, 32768.0 / 65535.0],
        ),
    ];
    for (acc, want) in cases {
        let desc = format!("{} {}", acc.0, acc.1);
        let p = write_attrs(
            &dir,
            &[(5126, "VEC3", false, pos.clone()), acc],
            r#""POSITION": 0, "COLOR_0": 1"#,
            r#", "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 1, 1]}}]"#,
        );
        let s = Scene::load(&p).unwrap_or_else(|e| panic!("{desc}: {e}"));
        let m = &s.meshes[0];
        let want = glam::Vec4::from(want);
        assert!(
            (m.colors[1] - want).abs().max_element() < 1e-6,
            "{desc}: {}",
            m.colors[1]
        );
        // The colour multiplies the material's base colour factor at any point of the triangle.
        let mat = &s.materials[m.material as usize];
        let c = s.base_color(mat, m.uv_at(0, 0.3, 0.3));
        let expect = want * glam::Vec4::new(0.5, 1.0, 1.0, 1.0);
        assert!((c - expect).abs().max_element() < 1e-6, "{desc}: {c}");
    }
}

#[test]
fn animation_pointer_moves_factors_lights_and_fov() {
    // Keys at t = 0 and 1: base colour red -> blue, 0 -> 4 (emissive strength, light intensity),
    // yfov 0.5 -> 1.5, and the light's node from the origin to y = 2.
    let floats: Vec<f32> = TRI
        .iter()
        .flatten()
        .copied()
        .chain([0.0, 1.0])
        .chain([1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0])
        .chain([0.0, 4.0])
        .chain([0.5, 1.5])
        .chain([0.0, 0.0, 0.0, 0.0, 2.0, 0.0])
        .collect();
    let data: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let ptr = |sampler: usize, p: &str| {
        format!(
            r#"{{"sampler": {sampler}, "target": {{"path": "pointer", "extensions": {{"KHR_animation_pointer": {{"pointer": "{p}"}}}}}}}}"#
        )
    };
    let channels = [
        ptr(0, "/materials/0/pbrMetallicRoughness/baseColorFactor"),
        ptr(
            1,
            "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength",
        ),
        ptr(1, "/extensions/KHR_lights_punctual/lights/0/intensity"),
        ptr(2, "/cameras/0/perspective/yfov"),
        ptr(3, "/nodes/2/translation"),
        ptr(1, "/materials/0/occlusionTexture/strength"),
    ]
    .join(",\n");
    let members = format!(
        r#""extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_animation_pointer"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "point", "color": [1, 0.5, 0.25], "intensity": 10}}]}}}},
  "bufferViews": [{{"buffer": 0, "byteLength": {len}}}],
  "accessors": [
{{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
{{"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 2, "type": "SCALAR"}},
{{"bufferView": 0, "byteOffset": 44, "componentType": 5126, "count": 2, "type": "VEC4"}},
{{"bufferView": 0, "byteOffset": 76, "componentType": 5126, "count": 2, "type": "SCALAR"}},
{{"bufferView": 0, "byteOffset": 84, "componentType": 5126, "count": 2, "type": "SCALAR"}},
{{"bufferView": 0, "byteOffset": 92, "componentType": 5126, "count": 2, "type": "VEC3"}}
  ],
  "materials": [{{"emissiveFactor": [1, 1, 1],
                 "extensions": {{"KHR_materials_emissive_strength": {{"emissiveStrength": 2}}}}}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}}],
  "cameras": [{{"type": "perspective", "perspective": {{"yfov": 0.8, "znear": 0.1}}}}],
  "nodes": [{{"mesh": 0}}, {{"camera": 0, "translation": [0, 0, 5]}},
            {{"extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}],
  "scenes": [{{"nodes": [0, 1, 2]}}],
  "animations": [{{"channels": [{channels}],
    "samplers": [{{"input": 1, "output": 2}}, {{"input": 1, "output": 3}},
                 {{"input": 1, "output": 4}}, {{"input": 1, "output": 5}}]}}]"#,
        len = data.len(),
    );
    let dir = tempfile::tempdir().unwrap();
    let p = write_doc(&dir, "ptr.gltf", &data, &members);
    let scene = Scene::load(&p).unwrap();
    assert_eq!(scene.warnings.len(), 1, "{:?}", scene.warnings);
    assert!(scene.warnings[0].contains("occlusionTexture/strength"));
    // Unposed: the file's rest values.
    assert_eq!(scene.materials[0].emissive, Vec3::splat(2.0));
    let a = scene
        .animation
        .as_ref()
        .expect("pointer channels animate the file");
    assert_eq!(a.duration(), 1.0);
    let mut s = scene.clone();
    crate::scene::animation::pose(&mut s, 0.5, [0.0, 0.0]);
    let m = &s.materials[0];
    assert_eq!(m.base_color, glam::Vec4::new(0.5, 0.0, 0.5, 1.0));
    assert_eq!(
        m.emissive,
        Vec3::splat(2.0),
        "strength 2 at t = 0.5, factor 1"
    );
    assert_eq!(
        s.lights[0],
        Light::Point(PointLight {
            position: Vec3::new(0.0, 1.0, 0.0),
            intensity: Vec3::new(2.0, 1.0, 0.5),
        })
    );
    match s.cameras[0].projection {
        Projection::Perspective { yfov, .. } => assert_eq!(yfov, 1.0),
        ref p => panic!("{p:?}"),
    }
    // Past the last key the values hold.
    let mut s = scene.clone();
    crate::scene::animation::pose(&mut s, 9.0, [0.0, 0.0]);
    assert_eq!(s.materials[0].emissive, Vec3::splat(4.0));
    assert_eq!(
        s.materials[0].base_color,
        glam::Vec4::new(0.0, 0.0, 1.0, 1.0)
    );
}

#[test]
fn animation_pointer_with_a_bad_sampler_or_type_is_an_error() {
    let data: Vec<u8> = TRI
        .iter()
        .flatten()
        .copied()
        .chain([0.0, 1.0, 0.0, 4.0])
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let doc = |sampler: usize, pointer: &str| {
        format!(
            r#""bufferViews": [{{"buffer": 0, "byteLength": {len}}}],
  "accessors": [
{{"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"}},
{{"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 2, "type": "SCALAR"}},
{{"bufferView": 0, "byteOffset": 44, "componentType": 5126, "count": 2, "type": "SCALAR"}}
  ],
  "materials": [{{}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "material": 0}}]}}],
  "nodes": [{{"mesh": 0}}],
  "animations": [{{"channels": [{{"sampler": {sampler}, "target": {{"path": "pointer",
      "extensions": {{"KHR_animation_pointer": {{"pointer": "{pointer}"}}}}}}}}],
    "samplers": [{{"input": 1, "output": 2}}]}}]"#,
            len = data.len(),
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let load = |members: String| {
        Scene::load(&write_doc(&dir, "bad.gltf", &data, &members))
            .map(|_| ())
            .map_err(|e| e.to_string())
    };
    assert!(load(doc(0, "/materials/0/pbrMetallicRoughness/roughnessFactor")).is_ok());
    let e = load(doc(3, "/materials/0/pbrMetallicRoughness/roughnessFactor")).unwrap_err();
    assert!(e.contains("no sampler 3"), "{e}");
    let e = load(doc(0, "/materials/0/emissiveFactor")).unwrap_err();
    assert!(e.contains("Scalar") && e.contains("Vec3"), "{e}");
    // A pointer at an element the file lacks is held, with a warning.
    let s = Scene::load(&write_doc(
        &dir,
        "far.gltf",
        &data,
        &doc(0, "/materials/7/pbrMetallicRoughness/roughnessFactor"),
    ))
    .unwrap();
    assert!(
        s.warnings.iter().any(|w| w.contains("/materials/7/")),
        "{:?}",
        s.warnings
    );
}

#[test]
fn scenes_are_chosen_by_index_or_name_and_default_to_the_files() {
    use crate::scene::{LoadOptions, SceneChoice};
    let dir = tempfile::tempdir().unwrap();
    let p = write(
        &dir,
        &TRI,
        &[],
        r#""nodes": [{"mesh": 0}, {"mesh": 0, "translation": [5, 0, 0]}],
  "scenes": [{"name": "left", "nodes": [0]}, {"name": "right", "nodes": [1]}],
  "scene": 1"#,
    );
    let x_of = |scene: SceneChoice| {
        let s = Scene::load_with(
            &p,
            &LoadOptions {
                scene,
                ..Default::default()
            },
        )
        .map_err(|e| e.to_string())?;
        assert_eq!(s.instances.len(), 1);
        assert_eq!(s.stats.scenes, vec!["0 'left'", "1 'right'"]);
        Ok::<f32, String>(s.bounds().min.x)
    };
    assert_eq!(
        x_of(SceneChoice::Default),
        Ok(5.0),
        "the file's default scene"
    );
    assert_eq!(x_of(SceneChoice::Index(0)), Ok(0.0));
    assert_eq!(x_of(SceneChoice::Name("right".into())), Ok(5.0));
    let e = x_of(SceneChoice::Index(2)).unwrap_err();
    assert!(e.contains("no scene 2") && e.contains("1 'right'"), "{e}");
    let e = x_of(SceneChoice::Name("middle".into())).unwrap_err();
    assert!(e.contains("no scene 'middle'"), "{e}");
}
