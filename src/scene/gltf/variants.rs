//! KHR_materials_variants read from the file: the root's variant names and each primitive's
//! mappings, checked against the variants and materials that exist.

use gltf::json::Value;

use super::Loader;
use crate::scene::variants::VariantMapping;

/// The variant names of the root `KHR_materials_variants` object, in file order (a variant
/// without a name is called by its index).
pub(super) fn names(doc: &gltf::Document) -> Vec<String> {
    let Some(list) = doc
        .extension_value("KHR_materials_variants")
        .and_then(|v| v.get("variants"))
        .and_then(Value::as_array)
    else {
        return Vec::new();
    };
    list.iter()
        .enumerate()
        .map(|(i, v)| match v.get("name").and_then(Value::as_str) {
            Some(n) => n.to_owned(),
            None => format!("variant {i}"),
        })
        .collect()
}

impl Loader<'_> {
    /// Records the variant mappings of primitive `prim`, built as scene mesh `mesh`; a mapping that
    /// names a missing variant or material draws a warning and is left out.
    pub(super) fn variant_mappings(&mut self, prim: &gltf::Primitive, mesh: u32, label: &str) {
        let Some(mappings) = prim
            .extension_value("KHR_materials_variants")
            .and_then(|v| v.get("mappings"))
            .and_then(Value::as_array)
        else {
            return;
        };
        let (variants, materials) = (
            self.scene.variants.names.len() as u64,
            self.doc.materials().len() as u64,
        );
        for (k, m) in mappings.iter().enumerate() {
            let material = m.get("material").and_then(Value::as_u64);
            let Some(material) = material.filter(|&i| i < materials) else {
                self.scene.warnings.push(format!(
                    "{label}: KHR_materials_variants mapping {k} names no existing material; ignored"
                ));
                continue;
            };
            let list = m.get("variants").and_then(Value::as_array);
            for v in list.into_iter().flatten() {
                match v.as_u64().filter(|&i| i < variants) {
                    Some(variant) => self.scene.variants.mappings.push(VariantMapping {
                        mesh,
                        variant: variant as u32,
                        material: material as u32,
                    }),
                    None => self.scene.warnings.push(format!(
                        "{label}: KHR_materials_variants mapping {k} names variant {v}, which does not exist; ignored"
                    )),
                }
            }
        }
    }
}
