//! The layering rule, checked: every `crate::` path in src/ names a module at a lower layer than the
//! file's own, so data flows one way (file -> Scene -> accel -> integrator -> film -> file).

use std::collections::BTreeSet;
use std::path::Path;

/// The layers, bottom up. A module may use the modules of lower layers only (not those of its own
/// layer: siblings stay independent). `sample` and `film` are leaves over `geometry`, so the scene
/// may name a sampler or filter kind in its settings without reaching up.
const LAYERS: &[&[&str]] = &[
    &["geometry"],
    &["sample", "film"],
    &["csg"],
    &["scene"],
    &["accel"],
    &["render"],
    &["bench", "turntable"],
    &["cli"],
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&module))
}

/// The module's code without its unit tests (a `#[cfg(test)]` module and everything after it), which
/// may build scenes and trace rays through any layer.
fn non_test_code(text: &str) -> &str {
    match text.find("#[cfg(test)]") {
        Some(i) => &text[..i],
        None => text,
    }
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// (file, its module, the modules it uses) for every library file outside unit tests.
fn uses() -> Vec<(String, String, BTreeSet<String>)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut out = Vec::new();
    for path in files {
        let rel = path.strip_prefix(&src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let module = first.trim_end_matches(".rs").to_string();
        if module == "lib" || module == "main" {
            continue;
        }
        // Files compiled only for tests.
        let name = rel.file_name().unwrap().to_string_lossy();
        if name == "tests.rs" || name == "testing.rs" {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let code = non_test_code(&text);
        let mut used = BTreeSet::new();
        for (i, _) in code.match_indices("crate::") {
            let rest = &code[i + "crate::".len()..];
            let end = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            let m = &rest[..end];
            // A grouped `use crate::{a, b}` would hide its modules from this scan.
            assert!(
                !m.is_empty(),
                "{}: write `use crate::module::...` paths, not `crate::{{...}}`",
                rel.display()
            );
            if m != module {
                used.insert(m.to_string());
            }
        }
        out.push((rel.display().to_string(), module, used));
    }
    out
}

#[test]
fn every_module_uses_only_lower_layers() {
    let mut wrong = Vec::new();
    let all = uses();
    assert!(all.len() > 50, "found only {} source files", all.len());
    for (file, module, used) in &all {
        let own =
            layer_of(module).unwrap_or_else(|| panic!("{file}: module '{module}' has no layer"));
        for m in used {
            match layer_of(m) {
                Some(l) if l < own => {}
                _ => wrong.push(format!("{file} ({module}) uses crate::{m}")),
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "upward or sideways uses:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn the_checker_sees_uses() {
    // The scan must find real edges, or the rule above would pass vacuously.
    let all = uses();
    let render_uses_scene = all
        .iter()
        .any(|(_, m, used)| m == "render" && used.contains("scene"));
    assert!(render_uses_scene);
    assert_eq!(
        non_test_code("a\n#[cfg(test)]\nmod tests { crate::cli }"),
        "a\n"
    );
}
