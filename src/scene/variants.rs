//! KHR_materials_variants: the named material sets of a file and which material each mesh takes in
//! each of them; choosing one re-dresses the meshes before rendering.

/// One mesh's material under one variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VariantMapping {
    /// Index in `Scene::meshes`.
    pub mesh: u32,
    /// Index in `MaterialVariants::names`.
    pub variant: u32,
    /// Index in `Scene::materials`.
    pub material: u32,
}

/// The variants a scene offers: their names in file order and the mappings of every mesh that
/// changes with them (a mesh without a mapping for the chosen variant keeps its default material,
/// as the extension says).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MaterialVariants {
    pub names: Vec<String>,
    pub mappings: Vec<VariantMapping>,
}

/// A variant name the scene does not offer.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum VariantError {
    #[error("no material variant '{0}': the file has no KHR_materials_variants")]
    NoVariants(String),
    #[error("no material variant '{name}' (the file has {}: {})", known.len(), known.join(", "))]
    Unknown { name: String, known: Vec<String> },
}

impl MaterialVariants {
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The index of variant `name`, or an error listing the known ones.
    pub fn find(&self, name: &str) -> Result<u32, VariantError> {
        if self.names.is_empty() {
            return Err(VariantError::NoVariants(name.to_owned()));
        }
        // File names are not unique by the spec; the first one wins, as in the Khronos viewer's menu.
        self.names
            .iter()
            .position(|n| n == name)
            .map(|i| i as u32)
            .ok_or_else(|| VariantError::Unknown {
                name: name.to_owned(),
                known: self.names.clone(),
            })
    }

    /// The material of each mesh under variant `name` (`materials[mesh]` updated in place).
    pub fn apply(&self, name: &str, materials: &mut [u32]) -> Result<(), VariantError> {
        let v = self.find(name)?;
        for m in self.mappings.iter().filter(|m| m.variant == v) {
            if let Some(slot) = materials.get_mut(m.mesh as usize) {
                *slot = m.material;
            }
        }
        Ok(())
    }

    /// Adds `other`'s variants (meshes numbered from `mesh0`, materials through `material_index`);
    /// a name both offer becomes one variant, so choosing it re-dresses every asset that has it.
    pub fn append(&mut self, other: &MaterialVariants, mesh0: u32, material_index: &[u32]) {
        for m in &other.mappings {
            let name = &other.names[m.variant as usize];
            let variant = match self.names.iter().position(|n| n == name) {
                Some(i) => i as u32,
                None => {
                    self.names.push(name.clone());
                    (self.names.len() - 1) as u32
                }
            };
            self.mappings.push(VariantMapping {
                mesh: m.mesh + mesh0,
                variant,
                material: material_index[m.material as usize],
            });
        }
        for n in &other.names {
            if !self.names.contains(n) {
                self.names.push(n.clone());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two() -> MaterialVariants {
        MaterialVariants {
            names: vec!["red".into(), "blue".into()],
            mappings: vec![
                VariantMapping {
                    mesh: 0,
                    variant: 0,
                    material: 2,
                },
                VariantMapping {
                    mesh: 1,
                    variant: 1,
                    material: 3,
                },
            ],
        }
    }

    #[test]
    fn a_variant_re_dresses_only_its_meshes() {
        let v = two();
        let mut mats = vec![0, 1, 1];
        v.apply("red", &mut mats).unwrap();
        assert_eq!(mats, vec![2, 1, 1]);
        let mut mats = vec![0, 1, 1];
        v.apply("blue", &mut mats).unwrap();
        assert_eq!(mats, vec![0, 3, 1]);
    }

    #[test]
    fn unknown_names_are_refused_listing_the_known_ones() {
        let err = two().apply("green", &mut [0, 0]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "no material variant 'green' (the file has 2: red, blue)"
        );
        let none = MaterialVariants::default().find("red").unwrap_err();
        assert!(none.to_string().contains("no KHR_materials_variants"));
    }

    #[test]
    fn appending_merges_names_and_renumbers() {
        let mut a = two();
        let b = MaterialVariants {
            names: vec!["blue".into(), "green".into()],
            mappings: vec![VariantMapping {
                mesh: 0,
                variant: 0,
                material: 1,
            }],
        };
        a.append(&b, 5, &[7, 8]);
        assert_eq!(a.names, vec!["red", "blue", "green"]);
        assert_eq!(
            a.mappings[2],
            VariantMapping {
                mesh: 5,
                variant: 1,
                material: 8
            }
        );
    }
}
