//! OBJ loader (placeholder until written).
use std::path::Path;

use super::{LoadError, Scene};

pub fn load(path: &Path) -> Result<Scene, LoadError> {
    Err(LoadError::new(path, "OBJ loading not written yet"))
}
