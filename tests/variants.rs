//! KHR_materials_variants: the generated two-quad asset and MaterialsVariantsShoe dress their meshes
//! as each variant says, renders show it, `glint info` lists the variants and extensions, and an
//! unknown name is refused listing the known ones (command line and scene files alike).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use glint::render::RenderSettings;
use glint::Scene;

fn variants_asset() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/variants/variants.gltf")
}

/// The material names of the meshes named `left` and `right`.
fn dress(scene: &Scene) -> (String, String) {
    let of = |name: &str| {
        let m = scene.meshes.iter().find(|m| m.name == name).unwrap();
        scene.materials[m.material as usize].name.clone()
    };
    (of("left"), of("right"))
}

#[test]
fn each_variant_dresses_the_quads_as_the_file_maps_them() {
    let scene = Scene::load(&variants_asset()).unwrap();
    assert_eq!(scene.variants.names, ["warm", "cool", "plain"]);
    assert_eq!(dress(&scene), ("grey".into(), "grey".into()));
    for (variant, want) in [
        ("warm", ("red", "gold")),
        ("cool", ("blue", "gold")),
        ("plain", ("grey", "grey")),
    ] {
        let mut s = scene.clone();
        s.select_variant(variant).unwrap();
        assert_eq!(dress(&s), (want.0.into(), want.1.into()), "{variant}");
    }
    let err = scene.clone().select_variant("hot").unwrap_err().to_string();
    assert!(
        err.contains("variants.gltf") && err.contains("'hot'") && err.contains("warm, cool, plain"),
        "{err}"
    );
}

/// Mean linear RGB of the left and right halves of an image.
fn halves(img: &glint::film::Image) -> [glam::Vec3; 2] {
    let mut sum = [glam::Vec3::ZERO; 2];
    for y in 0..img.height {
        for x in 0..img.width {
            sum[(2 * x >= img.width) as usize] += img.get(x, y).truncate();
        }
    }
    sum.map(|s| s / (img.width * img.height / 2) as f32)
}

#[test]
fn the_render_shows_the_chosen_variant() {
    let settings = RenderSettings {
        width: 48,
        height: 24,
        spp: 4,
        max_depth: 2,
        ..Default::default()
    };
    let mut out = Vec::new();
    for v in ["warm", "cool", "plain"] {
        let mut scene = Scene::load(&variants_asset()).unwrap();
        scene.select_variant(v).unwrap();
        let setup = glint::render::job::Setup::new(
            scene,
            &common::render_options(settings.width, settings.height),
        )
        .unwrap();
        let scene = std::sync::Arc::new(setup.scene);
        let backend = common::render_backends()[0];
        out.push(halves(&common::render_with(
            &scene,
            &setup.camera,
            backend,
            &settings,
        )));
    }
    let [warm, cool, plain] = [out[0], out[1], out[2]];
    // The halves hold the background too; against the plain (grey) render, the left quad turns red
    // under warm and blue under cool.
    let (w, c) = (warm[0] - plain[0], cool[0] - plain[0]);
    assert!(
        w.x > 0.02 && w.z < -0.02,
        "warm left {:?} vs {:?}",
        warm[0],
        plain[0]
    );
    assert!(
        c.z > 0.02 && c.x < -0.02,
        "cool left {:?} vs {:?}",
        cool[0],
        plain[0]
    );
    // The right quad is gold in both warm and cool, yellower than plain grey.
    // Light bounced off the left quad reaches it, so the halves agree to a little.
    assert!((warm[1] - cool[1]).abs().max_element() < 0.01 * warm[1].max_element());
    let g = warm[1] - plain[1];
    assert!(
        g.x - g.z > 0.02,
        "gold right {:?} vs {:?}",
        warm[1],
        plain[1]
    );
}

#[test]
fn the_shoe_offers_three_variants_each_with_its_own_base_colour_texture() {
    let Some(shared) = common::shared_assets() else {
        return;
    };
    let path = shared.join("gltf/MaterialsVariantsShoe/glTF/MaterialsVariantsShoe.gltf");
    let scene = Scene::load(&path).unwrap();
    assert_eq!(scene.variants.names, ["midnight", "beach", "street"]);
    let mut textures = Vec::new();
    for v in ["midnight", "beach", "street"] {
        let mut s = scene.clone();
        s.select_variant(v).unwrap();
        let mat = &s.materials[s.meshes[0].material as usize];
        textures.push(mat.base_color_tex.unwrap().texture);
    }
    textures.dedup();
    assert_eq!(textures.len(), 3, "{textures:?}");
}

fn glint(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(args)
        .output()
        .expect("run glint")
}

#[test]
fn info_lists_variants_and_extensions() {
    let o = glint(&["info", variants_asset().to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    assert!(text.contains("variants    warm, cool, plain"), "{text}");
    assert!(
        text.contains("extensions used     KHR_materials_variants (supported)"),
        "{text}"
    );
    // A file using an extension glint lacks: marked, and required ones listed apart.
    let dir = tempfile::tempdir().unwrap();
    let mut doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(variants_asset()).unwrap()).unwrap();
    doc["extensionsUsed"] = serde_json::json!(["KHR_materials_variants", "KHR_foo_bar"]);
    doc["extensionsRequired"] = serde_json::json!(["KHR_materials_variants"]);
    let f = dir.path().join("x.gltf");
    std::fs::write(&f, doc.to_string()).unwrap();
    let o = glint(&["info", f.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("KHR_foo_bar (not supported)"), "{text}");
    assert!(
        text.contains("extensions required KHR_materials_variants (supported)"),
        "{text}"
    );
}

#[test]
fn render_and_turntable_take_variant_and_refuse_unknown_names() {
    let dir = tempfile::tempdir().unwrap();
    let input = variants_asset();
    let still = dir.path().join("x.png");
    let small = ["--width", "16", "--height", "8", "--spp", "1", "--quiet"];
    let run = |cmd: &str, variant: &str| {
        // Each sequence in its own folder: a finished one is not loaded again.
        let frames = dir.path().join(format!("frames-{variant}"));
        let out = if cmd == "turntable" { &frames } else { &still };
        let mut args = vec![cmd, input.to_str().unwrap(), "-o", out.to_str().unwrap()];
        args.extend(small);
        args.extend(["--variant", variant]);
        if cmd == "turntable" {
            args.extend(["--frames", "1"]);
        }
        glint(&args)
    };
    for cmd in ["render", "turntable"] {
        let o = run(cmd, "cool");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let o = run(cmd, "hot");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.contains("no material variant 'hot' (the file has 3: warm, cool, plain)"),
            "{err}"
        );
    }
}

#[test]
fn scene_files_choose_an_assets_variant() {
    let dir = tempfile::tempdir().unwrap();
    let write = |variant: &str| {
        let f = dir.path().join("s.toml");
        std::fs::write(
            &f,
            format!(
                "[[asset]]\npath = {:?}\nvariant = \"{variant}\"\n",
                variants_asset()
            ),
        )
        .unwrap();
        f
    };
    let scene = Scene::load(&write("cool")).unwrap();
    assert_eq!(dress(&scene), ("blue".into(), "gold".into()));
    let err = Scene::load(&write("hot")).unwrap_err().to_string();
    assert!(
        err.contains("line 3") && err.contains("warm, cool, plain"),
        "{err}"
    );
    // The combined scene keeps the asset's variants, so --variant still works on it.
    let mut scene = Scene::load(&write("cool")).unwrap();
    scene.select_variant("warm").unwrap();
    assert_eq!(dress(&scene), ("red".into(), "gold".into()));
}
