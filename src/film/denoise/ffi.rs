//! The OIDN call sequence behind `Denoiser`: device set-up, the filters for the guides and the beauty,
//! each call followed by a look at the device's error (a wrong argument otherwise gives a black image).

use std::ffi::{c_char, c_void, CStr};

use super::oidn::{self, Device, Filter};
use super::{DenoiseError, DenoiseOptions, DenoiseQuality, GuideMode, Guides};
use crate::film::Image;

/// The device's pending error, if any (reading it clears it).
fn check(device: Device, what: &str) -> Result<(), DenoiseError> {
    let mut msg: *const c_char = std::ptr::null();
    // SAFETY: a live device; OIDN writes a pointer to a string it owns, valid until the next call.
    let code = unsafe { oidn::oidnGetDeviceError(device, &mut msg) };
    if code == oidn::ERROR_NONE {
        return Ok(());
    }
    let text = if msg.is_null() {
        format!("error {code}")
    } else {
        // SAFETY: non-null, NUL-terminated, owned by the device.
        unsafe { CStr::from_ptr(msg) }
            .to_string_lossy()
            .into_owned()
    };
    Err(DenoiseError::Oidn(format!("{what}: {text}")))
}

pub(super) fn new_device(threads: usize) -> Result<Device, DenoiseError> {
    // SAFETY: plain constructor; a null device means the library or its CPU device failed to load.
    let device = unsafe { oidn::oidnNewDevice(oidn::DEVICE_TYPE_CPU) };
    if device.is_null() {
        return Err(DenoiseError::Oidn(
            "no CPU device (is libOpenImageDenoise_device_cpu beside the library?)".into(),
        ));
    }
    if threads > 0 {
        // SAFETY: a live device, a NUL-terminated parameter name.
        unsafe { oidn::oidnSetDeviceInt(device, c"numThreads".as_ptr(), threads as i32) };
    }
    // SAFETY: a live device.
    unsafe { oidn::oidnCommitDevice(device) };
    if let Err(e) = check(device, "creating the CPU device") {
        // SAFETY: released once, here, since the caller never gets it.
        unsafe { oidn::oidnReleaseDevice(device) };
        return Err(e);
    }
    Ok(device)
}

/// A filter that releases itself.
struct OwnedFilter(Filter);

impl Drop for OwnedFilter {
    fn drop(&mut self) {
        // SAFETY: from oidnNewFilter, released once.
        unsafe { oidn::oidnReleaseFilter(self.0) }
    }
}

/// Runs one RT filter: `images` are (name, FLOAT3 buffer) pairs shared with the filter, read or
/// written in place (`output` may alias an input, as the guides' own passes do).
fn execute(
    device: Device,
    (width, height): (usize, usize),
    images: &[(&CStr, *mut f32)],
    flags: &[(&CStr, bool)],
    quality: DenoiseQuality,
) -> Result<(), DenoiseError> {
    // SAFETY: a live device and a NUL-terminated filter type.
    let filter = OwnedFilter(unsafe { oidn::oidnNewFilter(device, c"RT".as_ptr()) });
    check(device, "creating the RT filter")?;
    for (name, ptr) in images.iter() {
        // SAFETY: each buffer holds width * height * 3 floats and outlives the filter's execution
        // (the caller owns them across this call); strides 0 mean tightly packed.
        unsafe {
            oidn::oidnSetSharedFilterImage(
                filter.0,
                name.as_ptr(),
                *ptr as *mut c_void,
                oidn::FORMAT_FLOAT3,
                width,
                height,
                0,
                0,
                0,
            )
        };
        check(device, &format!("setting image {}", name.to_string_lossy()))?;
    }
    let q = match quality {
        DenoiseQuality::Fast => oidn::QUALITY_FAST,
        DenoiseQuality::Balanced => oidn::QUALITY_BALANCED,
        DenoiseQuality::High => oidn::QUALITY_HIGH,
    };
    // SAFETY: a live filter and NUL-terminated parameter names.
    unsafe {
        for (name, value) in flags {
            oidn::oidnSetFilterBool(filter.0, name.as_ptr(), *value);
        }
        oidn::oidnSetFilterInt(filter.0, c"quality".as_ptr(), q);
        oidn::oidnCommitFilter(filter.0);
    }
    check(device, "committing the filter")?;
    // SAFETY: a committed filter whose images are alive.
    unsafe { oidn::oidnExecuteFilter(filter.0) };
    check(device, "denoising")
}

/// The denoised RGB (3 floats a pixel) of `color`, steered by `guides` if given.
pub(super) fn run(
    device: Device,
    options: DenoiseOptions,
    color: &Image,
    guides: Option<Guides>,
) -> Result<Vec<f32>, DenoiseError> {
    let size = (color.width, color.height);
    let flat = |v: &mut dyn Iterator<Item = [f32; 3]>| v.flatten().collect::<Vec<f32>>();
    let mut rgb = flat(&mut color.pixels.iter().map(|p| p.truncate().to_array()));
    let mut out = vec![0.0f32; rgb.len()];
    let Some(g) = guides else {
        let images = [(c"color", rgb.as_mut_ptr()), (c"output", out.as_mut_ptr())];
        execute(device, size, &images, &[(c"hdr", true)], options.quality)?;
        return Ok(out);
    };
    let mut albedo = flat(&mut g.albedo.iter().map(|a| a.to_array()));
    let mut normal = flat(&mut g.normal.iter().map(|n| n.to_array()));
    let mode = options.guides.resolve(g.samples);
    if mode == GuideMode::Prefiltered {
        // Each guide cleaned by an RT filter of its own, in place.
        for (name, buf) in [(c"albedo", &mut albedo), (c"normal", &mut normal)] {
            let p = buf.as_mut_ptr();
            execute(
                device,
                size,
                &[(name, p), (c"output", p)],
                &[],
                options.prefilter,
            )?;
        }
    }
    let images = [
        (c"color", rgb.as_mut_ptr()),
        (c"albedo", albedo.as_mut_ptr()),
        (c"normal", normal.as_mut_ptr()),
        (c"output", out.as_mut_ptr()),
    ];
    let clean = mode != GuideMode::Noisy;
    let flags = [(c"hdr", true), (c"cleanAux", clean)];
    execute(device, size, &images, &flags, options.quality)?;
    Ok(out)
}
