//! glTF 2.0 loader (placeholder until written).
use std::path::Path;

use super::{LoadError, Scene};

pub fn load(path: &Path) -> Result<Scene, LoadError> {
    Err(LoadError::new(path, "glTF loading not written yet"))
}
