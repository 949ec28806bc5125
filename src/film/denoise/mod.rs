//! Denoising a finished image with Intel Open Image Denoise 2 (the `denoise` feature): the RT filter in
//! HDR mode on the linear beauty, guided by albedo and normal images, prefiltered or as rendered.
//!
//! Without the feature the same API exists and `Denoiser::new` returns `DenoiseError::NotBuilt`, so
//! callers report a clear error instead of failing to build or crashing.

#[cfg(feature = "denoise")]
mod oidn;

use glam::Vec3;

use super::Image;

#[derive(Debug, thiserror::Error)]
pub enum DenoiseError {
    #[error(
        "this glint was built without the denoiser (cargo feature `denoise`, on by default; \
         rebuild without --no-default-features, or with --features denoise)"
    )]
    NotBuilt,
    #[error("Open Image Denoise: {0}")]
    Oidn(String),
    #[error("denoise: {what} has {got} pixels, the image {want}")]
    Size {
        what: &'static str,
        got: usize,
        want: usize,
    },
}

/// The network's trade of speed for quality (OIDN's `quality`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum DenoiseQuality {
    Fast,
    Balanced,
    /// OIDN's default for the RT filter on the CPU.
    #[default]
    High,
}

/// What the guides go through before they steer the beauty's pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum GuideMode {
    /// Prefiltered while a pixel's guides average fewer than `TRUSTED_FROM_SPP` samples, trusted
    /// from there: `glint bench denoise` found trusted guides within 2% of prefiltered ones' relMSE
    /// from 64 spp on (DamagedHelmet, 1280x720) in about half the time, and 12% worse at 16 spp.
    #[default]
    Auto,
    /// Each guide cleaned by an RT pass of its own, then declared noise-free (`cleanAux`): OIDN's
    /// highest-quality pipeline, three passes (Blender's "Accurate" prefilter).
    Prefiltered,
    /// As rendered, to the network trained on noisy guides: one pass, about the time of the colour
    /// alone (Blender's "Fast").
    Noisy,
    /// As rendered but declared noise-free (`cleanAux` with no prefilter): one pass of the large
    /// clean-guide network, right where only the pixel area varies what a pixel's samples see
    /// first (no depth of field, motion blur, stochastic first lobe, or texture detail finer than
    /// the samples resolve; Blender's "None").
    Trusted,
}

/// The samples a pixel's guides must average for `GuideMode::Auto` to trust them.
pub const TRUSTED_FROM_SPP: u32 = 64;

impl GuideMode {
    /// The mode used for guides that average at least `samples` samples in every pixel.
    pub fn resolve(self, samples: u32) -> GuideMode {
        match self {
            GuideMode::Auto if samples >= TRUSTED_FROM_SPP => GuideMode::Trusted,
            GuideMode::Auto => GuideMode::Prefiltered,
            mode => mode,
        }
    }
}

/// How to denoise: the network's quality and what the guides go through.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DenoiseOptions {
    pub quality: DenoiseQuality,
    pub guides: GuideMode,
    /// The quality of the guides' own cleaning passes (when they are prefiltered): balanced by
    /// default, which `glint bench denoise` measured at 64% of high's time for the whole guided
    /// denoise and within 2% of its relMSE against a converged reference (fast gives balanced's
    /// image in balanced's time).
    pub prefilter: DenoiseQuality,
}

impl Default for DenoiseOptions {
    fn default() -> Self {
        Self {
            quality: DenoiseQuality::High,
            guides: GuideMode::Auto,
            prefilter: DenoiseQuality::Balanced,
        }
    }
}

/// The guide images: per-pixel albedo and shading normal, as the beauty's samples saw them.
#[derive(Clone, Copy, Debug)]
pub struct Guides<'a> {
    pub albedo: &'a [Vec3],
    pub normal: &'a [Vec3],
    /// The fewest samples any pixel's guides average (what `GuideMode::Auto` decides by).
    pub samples: u32,
}

/// A denoising device (one per process is enough; creating it loads the library's CPU kernels).
pub struct Denoiser {
    #[cfg(feature = "denoise")]
    device: oidn::Device,
    #[cfg(not(feature = "denoise"))]
    never: std::convert::Infallible,
    options: DenoiseOptions,
}

impl Denoiser {
    /// Whether this build has the denoiser.
    pub const AVAILABLE: bool = cfg!(feature = "denoise");

    /// A CPU device with `threads` worker threads (0: the library decides).
    pub fn new(threads: usize, options: DenoiseOptions) -> Result<Self, DenoiseError> {
        #[cfg(feature = "denoise")]
        {
            Ok(Self {
                device: ffi::new_device(threads)?,
                options,
            })
        }
        #[cfg(not(feature = "denoise"))]
        {
            let _ = (threads, options);
            Err(DenoiseError::NotBuilt)
        }
    }

    /// The denoised image (alpha kept from `color`), steered by `guides` if given.
    pub fn denoise(&self, color: &Image, guides: Option<Guides>) -> Result<Image, DenoiseError> {
        let n = color.width * color.height;
        if let Some(g) = guides {
            for (what, got) in [("albedo", g.albedo.len()), ("normal", g.normal.len())] {
                if got != n {
                    return Err(DenoiseError::Size { what, got, want: n });
                }
            }
        }
        #[cfg(feature = "denoise")]
        {
            let rgb = ffi::run(self.device, self.options, color, guides)?;
            let mut out = color.clone();
            for (p, c) in out.pixels.iter_mut().zip(rgb.chunks_exact(3)) {
                *p = glam::Vec4::new(c[0], c[1], c[2], p.w);
            }
            Ok(out)
        }
        #[cfg(not(feature = "denoise"))]
        {
            let _ = self.options;
            match self.never {}
        }
    }
}

#[cfg(feature = "denoise")]
impl Drop for Denoiser {
    fn drop(&mut self) {
        // SAFETY: the device came from oidnNewDevice and is released once.
        unsafe { oidn::oidnReleaseDevice(self.device) }
    }
}

#[cfg(feature = "denoise")]
mod ffi;

#[cfg(all(test, feature = "denoise"))]
mod tests;

#[cfg(all(test, not(feature = "denoise")))]
mod not_built {
    #[test]
    fn a_build_without_the_feature_says_so() {
        let err = super::Denoiser::new(1, super::DenoiseOptions::default())
            .err()
            .unwrap();
        assert!(
            err.to_string().contains("built without the denoiser"),
            "{err}"
        );
    }
}
