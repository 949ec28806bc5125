//! The settings a scene file's `[render]` table may give and the command line may override, and the
//! one rule between them: a flag beats the file, the file beats the command's default.

use std::path::Path;

use super::JobError;
use crate::accel::Backend;
use crate::film::filter::FilterKind;
use crate::sample::SamplerKind;
use crate::scene::desc::FileSettings;
use crate::scene::{GgxScattering, Layering, ShadingModel};

/// Largest accepted image edge, in pixels.
pub const MAX_EDGE: usize = 32_768;
/// Largest accepted pixel count (the film holds 16 bytes a pixel: 2 GiB at this size).
pub const MAX_PIXELS: usize = 1 << 27;
/// Most samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;

/// Declares `Basics` (every setting), `Overrides` (each one maybe given) and `resolve` from one list,
/// so a setting cannot be added to one and forgotten in another.
macro_rules! overridable {
    ($($(#[$doc:meta])* $name:ident: $ty:ty,)*) => {
        /// The settings a scene file may give and the command line may override, all decided.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Basics {
            $($(#[$doc])* pub $name: $ty,)*
        }

        /// Some of `Basics`, as a scene file or the command line gives them (None: not given).
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct Overrides {
            $($(#[$doc])* pub $name: Option<$ty>,)*
        }

        impl Overrides {
            /// Every setting given: what a command passes when the scene file must not change them.
            pub fn all(b: Basics) -> Self {
                Self { $($name: Some(b.$name),)* }
            }
        }

        /// Each setting from `flags` when given there, else from `file`, else from `defaults`.
        pub fn resolve(defaults: Basics, file: &Overrides, flags: &Overrides) -> Basics {
            Basics { $($name: flags.$name.or(file.$name).unwrap_or(defaults.$name),)* }
        }
    };
}

overridable! {
    width: usize,
    height: usize,
    /// Samples per pixel.
    spp: u32,
    /// Bounces after the camera ray (1 = direct light only).
    max_depth: u32,
    seed: u64,
    sampler: SamplerKind,
    filter: FilterKind,
    backend: Backend,
    /// How the dielectric specular layer weights the diffuse under it.
    layering: Layering,
    /// Single- or multiple-scattering GGX.
    ggx: GgxScattering,
}

impl Default for Basics {
    /// What `glint render` uses when neither the command line nor the scene file says.
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            spp: 16,
            max_depth: 5,
            seed: 0,
            sampler: SamplerKind::default(),
            filter: FilterKind::default(),
            backend: Backend::default_available(),
            layering: Layering::default(),
            ggx: GgxScattering::default(),
        }
    }
}

/// Refuses an image size that cannot be rendered (or would not fit in memory); the benches trace
/// one ray per pixel of such an image and refuse the same sizes.
pub fn check_size(w: usize, h: usize) -> Result<(), JobError> {
    if w == 0 || h == 0 || w > MAX_EDGE || h > MAX_EDGE {
        return Err(JobError::EdgeOutOfRange(w, h));
    }
    if w * h > MAX_PIXELS {
        return Err(JobError::PixelsOutOfRange(w, h));
    }
    Ok(())
}

impl Basics {
    /// Refuses sizes and sample counts that cannot be rendered (or would not fit in memory).
    pub fn validate(&self) -> Result<(), JobError> {
        check_size(self.width, self.height)?;
        if self.spp == 0 || self.spp > MAX_SPP {
            return Err(JobError::SppOutOfRange(self.spp));
        }
        Ok(())
    }

    pub fn aspect(&self) -> f32 {
        self.width as f32 / self.height as f32
    }

    /// The shading model these settings choose.
    pub fn shading(&self) -> ShadingModel {
        ShadingModel {
            layering: self.layering,
            ggx: self.ggx,
        }
    }
}

/// A scene file's `[render]` settings as overrides. The file names its backend in words (the scene
/// layer does not know the backends); it is read only when `flags` leave the backend to the file.
pub fn file_overrides(
    s: &FileSettings,
    source: &Path,
    flags: &Overrides,
) -> Result<Overrides, JobError> {
    let backend = match (&s.backend, flags.backend) {
        (Some(name), None) => Some(name.parse().map_err(|message| JobError::FileBackend {
            path: source.to_path_buf(),
            message,
        })?),
        _ => None,
    };
    Ok(Overrides {
        width: s.width,
        height: s.height,
        spp: s.spp,
        max_depth: s.max_depth,
        seed: s.seed,
        sampler: s.sampler,
        filter: s.filter,
        backend,
        layering: s.layering,
        ggx: s.ggx,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_beat_the_file_and_the_file_beats_the_defaults() {
        let file = Overrides {
            width: Some(24),
            height: Some(18),
            spp: Some(2),
            ..Default::default()
        };
        let flags = Overrides {
            width: Some(30),
            ..Default::default()
        };
        let b = resolve(Basics::default(), &file, &flags);
        assert_eq!((b.width, b.height, b.spp, b.max_depth), (30, 18, 2, 5));
    }
}
