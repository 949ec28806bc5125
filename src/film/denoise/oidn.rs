//! The Open Image Denoise 2 C API, the dozen functions glint calls, declared by hand (`denoise` feature).
//! The only FFI of the film layer; `super` wraps it in a safe `Denoiser`.
//!
//! Why not the `oidn` crate (2.5.x would match): its build script finds the library through
//! pkg-config or an `OIDN_DIR` variable set in the environment of the build, and a dependent crate's
//! build.rs cannot set either for it. glint's build.rs fetches the library from the `pyoidn` wheel
//! when the build starts, so the crate would never see it (a plain `cargo build` would fail);
//! declaring the functions here lets that build script link them as it links Embree (search path and
//! rpath), with `OIDN_DIR` as the one override. Signatures follow `OpenImageDenoise/oidn.h` of 2.5.

use std::ffi::{c_char, c_void};

/// `OIDNDevice` and `OIDNFilter`: opaque handles.
pub type Device = *mut c_void;
pub type Filter = *mut c_void;

/// `OIDN_DEVICE_TYPE_CPU`.
pub const DEVICE_TYPE_CPU: i32 = 1;
/// `OIDN_FORMAT_FLOAT3`: an enum value, not a bit pattern (a wrong one gives "invalid image format").
pub const FORMAT_FLOAT3: i32 = 3;
/// `OIDN_ERROR_NONE`.
pub const ERROR_NONE: i32 = 0;
/// `OIDN_QUALITY_FAST`, `_BALANCED`, `_HIGH`.
pub const QUALITY_FAST: i32 = 4;
pub const QUALITY_BALANCED: i32 = 5;
pub const QUALITY_HIGH: i32 = 6;

#[link(name = "OpenImageDenoise")]
extern "C" {
    pub fn oidnNewDevice(device_type: i32) -> Device;
    pub fn oidnSetDeviceInt(device: Device, name: *const c_char, value: i32);
    pub fn oidnCommitDevice(device: Device);
    pub fn oidnGetDeviceError(device: Device, out_message: *mut *const c_char) -> i32;
    pub fn oidnReleaseDevice(device: Device);
    pub fn oidnNewFilter(device: Device, filter_type: *const c_char) -> Filter;
    #[allow(clippy::too_many_arguments)]
    pub fn oidnSetSharedFilterImage(
        filter: Filter,
        name: *const c_char,
        dev_ptr: *mut c_void,
        format: i32,
        width: usize,
        height: usize,
        byte_offset: usize,
        pixel_byte_stride: usize,
        row_byte_stride: usize,
    );
    pub fn oidnSetFilterBool(filter: Filter, name: *const c_char, value: bool);
    pub fn oidnSetFilterInt(filter: Filter, name: *const c_char, value: i32);
    pub fn oidnCommitFilter(filter: Filter);
    pub fn oidnExecuteFilter(filter: Filter);
    pub fn oidnReleaseFilter(filter: Filter);
}
