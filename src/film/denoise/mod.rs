//! Denoising a finished image with Intel Open Image Denoise 2 (the `denoise` feature): the RT filter in
//! HDR mode on the linear beauty, guided by albedo and normal images that are prefiltered first (`cleanAux`).
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

/// The guide images: per-pixel albedo and shading normal, as the beauty's samples saw them.
#[derive(Clone, Copy, Debug)]
pub struct Guides<'a> {
    pub albedo: &'a [Vec3],
    pub normal: &'a [Vec3],
}

/// A denoising device (one per process is enough; creating it loads the library's CPU kernels).
pub struct Denoiser {
    #[cfg(feature = "denoise")]
    device: oidn::Device,
    #[cfg(not(feature = "denoise"))]
    never: std::convert::Infallible,
    quality: DenoiseQuality,
    /// The quality of the guides' own cleaning passes: balanced by default, which `glint bench
    /// denoise` measured at 60% of high's time for the whole guided denoise (DamagedHelmet,
    /// 1280x720, 2 threads: 15.7 s against 26.0 s) and 3.8e-4 of the image's mean from it (fast
    /// gave the same image in the same time).
    prefilter: DenoiseQuality,
}

impl Denoiser {
    /// Whether this build has the denoiser.
    pub const AVAILABLE: bool = cfg!(feature = "denoise");

    /// A CPU device with `threads` worker threads (0: the library decides).
    pub fn new(threads: usize, quality: DenoiseQuality) -> Result<Self, DenoiseError> {
        #[cfg(feature = "denoise")]
        {
            Ok(Self {
                device: ffi::new_device(threads)?,
                quality,
                prefilter: DenoiseQuality::Balanced,
            })
        }
        #[cfg(not(feature = "denoise"))]
        {
            let _ = (threads, quality);
            Err(DenoiseError::NotBuilt)
        }
    }

    /// The same device with the guides cleaned at `prefilter` quality.
    pub fn with_prefilter(mut self, prefilter: DenoiseQuality) -> Self {
        self.prefilter = prefilter;
        self
    }

    /// The denoised image (alpha kept from `color`); with `guides`, they are cleaned by their own
    /// filter pass and then guide the beauty's (OIDN's recommended `cleanAux` pipeline).
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
            let rgb = ffi::run(self.device, (self.quality, self.prefilter), color, guides)?;
            let mut out = color.clone();
            for (p, c) in out.pixels.iter_mut().zip(rgb.chunks_exact(3)) {
                *p = glam::Vec4::new(c[0], c[1], c[2], p.w);
            }
            Ok(out)
        }
        #[cfg(not(feature = "denoise"))]
        {
            let _ = (self.quality, self.prefilter);
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
        let err = super::Denoiser::new(1, super::DenoiseQuality::Fast)
            .err()
            .unwrap();
        assert!(
            err.to_string().contains("built without the denoiser"),
            "{err}"
        );
    }
}
