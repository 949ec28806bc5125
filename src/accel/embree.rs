//! Embree 4 backend (placeholder until written).
use std::sync::Arc;

use super::{Accel, AccelError};
use crate::geometry::{Hit, Ray};
use crate::scene::Scene;

pub struct EmbreeAccel {
    _scene: Arc<Scene>,
}

impl EmbreeAccel {
    pub fn build(_scene: Arc<Scene>) -> Result<Self, AccelError> {
        Err(AccelError::Embree("not written yet".into()))
    }
}

impl Accel for EmbreeAccel {
    fn name(&self) -> &'static str {
        "embree"
    }
    fn intersect(&self, _ray: &Ray) -> Option<Hit> {
        None
    }
    fn occluded(&self, _ray: &Ray) -> bool {
        false
    }
}
