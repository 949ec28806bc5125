//! glTF images and textures: images decoded once to RGBA8 pixels (embedded, data URI or file), and
//! each (texture, sRGB or linear) pair added to the scene's textures on first use.

use std::rc::Rc;

use super::accessor::{uri_decodes, view_bytes};
use super::error::ImageError;
use super::Loader;
use crate::scene::{ktx2, Texture, Wrap};

/// Decoded image pixels, shared by the sRGB and linear variants of a texture.
pub(super) struct Pixels {
    width: usize,
    height: usize,
    rgba: Vec<[u8; 4]>,
}

impl Loader<'_> {
    /// The scene texture of glTF texture `index` read as sRGB or linear; None when its image failed.
    pub(super) fn texture(&mut self, index: usize, srgb: bool) -> Option<u32> {
        if let Some(t) = self.textures.get(&(index, srgb)) {
            return *t;
        }
        let tex = self.doc.textures().nth(index)?;
        let image = tex.source();
        let pixels = self.image(&image);
        let out = pixels.map(|p| {
            let sampler = tex.sampler();
            let name = tex
                .name()
                .or(image.name())
                .map(str::to_owned)
                .or_else(|| match image.source() {
                    gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                        Some(uri.to_owned())
                    }
                    _ => None,
                })
                .unwrap_or_else(|| format!("texture {index}"));
            self.scene.textures.push(Texture {
                name,
                width: p.width,
                height: p.height,
                pixels: p.rgba.clone(),
                srgb,
                wrap_s: wrap(sampler.wrap_s()),
                wrap_t: wrap(sampler.wrap_t()),
            });
            (self.scene.textures.len() - 1) as u32
        });
        self.textures.insert((index, srgb), out);
        out
    }

    /// The pixels of an image, decoded on first use; None (with a warning) when it cannot be read.
    fn image(&mut self, image: &gltf::Image) -> Option<Rc<Pixels>> {
        let i = image.index();
        if let Some(p) = self.images.get(&i) {
            return p.clone();
        }
        // `Image::source` unwraps both of these, so they are checked before it is called.
        if let Err(e) = source_present(self.doc, i) {
            self.scene
                .warnings
                .push(format!("image {i}: {e}; the texture is ignored"));
            self.images.insert(i, None);
            return None;
        }
        let label = match image.source() {
            gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
                format!("image {i} ('{uri}')")
            }
            _ => format!("image {i}"),
        };
        let out = match self.decode_image(image) {
            Ok(p) => Some(Rc::new(p)),
            Err(e) => {
                self.scene
                    .warnings
                    .push(format!("{label}: {e}; the texture is ignored"));
                None
            }
        };
        self.images.insert(i, out.clone());
        out
    }

    fn decode_image(&self, image: &gltf::Image) -> Result<Pixels, ImageError> {
        match image.source() {
            gltf::image::Source::View { view, .. } => {
                let bytes = view_bytes(&view, self.buffers)?;
                if ktx2::is_ktx2(bytes) {
                    return Ok(Pixels::from(ktx2::decode(bytes)?));
                }
                let img = image::load_from_memory(bytes)
                    .map_err(ImageError::Decode)?
                    .to_rgba8();
                Ok(Pixels {
                    width: img.width() as usize,
                    height: img.height() as usize,
                    rgba: img.pixels().map(|p| p.0).collect(),
                })
            }
            gltf::image::Source::Uri { uri, mime_type } => {
                if !uri_decodes(uri) {
                    return Err(ImageError::MalformedUri);
                }
                if is_ktx2_uri(uri, mime_type) {
                    return self.decode_ktx2_uri(uri);
                }
                let d = gltf::image::Data::from_source(image.source(), Some(self.base), &[])
                    .map_err(|e| match e {
                        gltf::Error::Io(e) => ImageError::Io(e),
                        e => ImageError::Source(e),
                    })?;
                Ok(Pixels {
                    width: d.width as usize,
                    height: d.height as usize,
                    rgba: to_rgba8(&d)?,
                })
            }
        }
    }
}

impl Loader<'_> {
    /// A KTX2 image named by a URI (a file beside the glTF file or a data URI), decoded.
    fn decode_ktx2_uri(&self, uri: &str) -> Result<Pixels, ImageError> {
        let source = gltf::buffer::Source::Uri(uri);
        let bytes = gltf::buffer::Data::from_source_and_blob(source, Some(self.base), &mut None)
            .map_err(|e| match e {
                gltf::Error::Io(e) => ImageError::Io(e),
                e => ImageError::Source(e),
            })?;
        Ok(Pixels::from(ktx2::decode(&bytes.0)?))
    }
}

/// Whether a URI image is KTX2: by its MIME type or its file name. Files point textures straight
/// at .ktx2 images without KHR_texture_basisu too (the shared AnisotropyBarnLamp does).
fn is_ktx2_uri(uri: &str, mime_type: Option<&str>) -> bool {
    mime_type == Some("image/ktx2")
        || uri.starts_with("data:image/ktx2")
        || uri
            .rsplit('.')
            .next()
            .is_some_and(|e| e.eq_ignore_ascii_case("ktx2"))
}

impl From<ktx2::Rgba8> for Pixels {
    fn from(img: ktx2::Rgba8) -> Self {
        Self {
            width: img.width,
            height: img.height,
            rgba: img.pixels,
        }
    }
}

/// Texture extensions whose `source` glint decodes (WebP through the `image` crate, KTX2 through
/// `scene::ktx2`).
const SOURCE_EXTENSIONS: [&str; 2] = ["EXT_texture_webp", "KHR_texture_basisu"];

/// Points every texture at the image of an extension glint decodes, which the spec says a client
/// that supports the extension uses instead of (or when there is no) core `source`.
pub(super) fn prefer_extension_sources(root: &mut gltf::json::Root) {
    for tex in &mut root.textures {
        let ext = tex.extensions.as_ref().and_then(|e| {
            SOURCE_EXTENSIONS
                .iter()
                .find_map(|n| e.others.get(*n)?.get("source")?.as_u64())
        });
        if let Some(src) = ext.and_then(|s| u32::try_from(s).ok()) {
            tex.source = gltf::json::Index::new(src);
        }
    }
}

/// Whether image `i` has what the `gltf` crate's `Image::source` unwraps: a URI, or a buffer view with
/// a MIME type (which the spec requires there).
fn source_present(doc: &gltf::Document, i: usize) -> Result<(), ImageError> {
    let Some(json) = doc.as_json().images.get(i) else {
        return Err(ImageError::NoSource);
    };
    match (&json.buffer_view, &json.uri) {
        (Some(_), _) if json.mime_type.is_none() => Err(ImageError::NoMimeType),
        (None, None) => Err(ImageError::NoSource),
        _ => Ok(()),
    }
}

/// Converts any decoded glTF image into RGBA8 (grey formats replicate into RGB).
fn to_rgba8(img: &gltf::image::Data) -> Result<Vec<[u8; 4]>, ImageError> {
    use gltf::image::Format::*;
    let n = img.width as usize * img.height as usize;
    let p = &img.pixels;
    let (ch, bytes_per) = match img.format {
        R8 => (1, 1),
        R8G8 => (2, 1),
        R8G8B8 => (3, 1),
        R8G8B8A8 => (4, 1),
        R16 => (1, 2),
        R16G16 => (2, 2),
        R16G16B16 => (3, 2),
        R16G16B16A16 => (4, 2),
        R32G32B32FLOAT => (3, 4),
        R32G32B32A32FLOAT => (4, 4),
    };
    if p.len() < n * ch * bytes_per {
        return Err(ImageError::Short);
    }
    let get = |i: usize| -> u8 {
        match bytes_per {
            1 => p[i],
            2 => (u16::from_ne_bytes([p[2 * i], p[2 * i + 1]]) as u32 * 255 / 65535) as u8,
            _ => {
                let f = f32::from_ne_bytes([p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]]);
                (f.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
            }
        }
    };
    Ok((0..n)
        .map(|k| {
            let i = k * ch;
            match ch {
                1 => {
                    let g = get(i);
                    [g, g, g, 255]
                }
                2 => {
                    let g = get(i);
                    [g, g, g, get(i + 1)]
                }
                3 => [get(i), get(i + 1), get(i + 2), 255],
                _ => [get(i), get(i + 1), get(i + 2), get(i + 3)],
            }
        })
        .collect())
}

fn wrap(w: gltf::texture::WrappingMode) -> Wrap {
    match w {
        gltf::texture::WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        gltf::texture::WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
    }
}
