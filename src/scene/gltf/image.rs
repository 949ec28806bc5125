//! glTF images and textures: images decoded once to RGBA8 pixels (embedded, data URI or file), and
//! each (texture, sRGB or linear) pair added to the scene's textures on first use.

use std::rc::Rc;

use super::accessor::{uri_decodes, view_bytes};
use super::error::ImageError;
use super::Loader;
use crate::scene::{Texture, TextureFilter, Wrap};

/// Decoded image pixels, shared by the sRGB and linear variants of a texture.
pub(super) type Pixels = crate::scene::decode::Rgba8;

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
                pixels: p.pixels.clone(),
                srgb,
                wrap_s: wrap(sampler.wrap_s()),
                wrap_t: wrap(sampler.wrap_t()),
                filter: filter(sampler.min_filter(), sampler.mag_filter()),
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
        let file;
        let bytes = match image.source() {
            gltf::image::Source::View { view, .. } => view_bytes(&view, self.buffers)?,
            gltf::image::Source::Uri { uri, .. } => {
                if !uri_decodes(uri) {
                    return Err(ImageError::MalformedUri);
                }
                // The crate's URI reader (data URI or a file beside the glTF); the decoding is
                // glint's, so that the pixel cap holds for every image.
                file = gltf::buffer::Data::from_source(
                    gltf::buffer::Source::Uri(uri),
                    Some(self.base),
                )
                .map_err(|e| match e {
                    gltf::Error::Io(e) => ImageError::Io(e),
                    e => ImageError::Source(e),
                })?;
                &file.0[..]
            }
        };
        Ok(crate::scene::decode::decode_rgba8(bytes)?)
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

/// A sampler's filters as one (glint has no mip levels, so their part of a min filter is
/// dropped): nearest where every filter the sampler names is nearest, as Blender's importer
/// decides; linear where it names none, the usual choice the spec leaves to the renderer.
fn filter(
    min: Option<gltf::texture::MinFilter>,
    mag: Option<gltf::texture::MagFilter>,
) -> TextureFilter {
    use gltf::texture::{MagFilter, MinFilter};
    let min_nearest = min.map(|m| {
        matches!(
            m,
            MinFilter::Nearest | MinFilter::NearestMipmapNearest | MinFilter::NearestMipmapLinear
        )
    });
    let mag_nearest = mag.map(|m| m == MagFilter::Nearest);
    match (min_nearest, mag_nearest) {
        (Some(true), Some(true)) | (Some(true), None) | (None, Some(true)) => {
            TextureFilter::Nearest
        }
        _ => TextureFilter::Linear,
    }
}

fn wrap(w: gltf::texture::WrappingMode) -> Wrap {
    match w {
        gltf::texture::WrappingMode::ClampToEdge => Wrap::ClampToEdge,
        gltf::texture::WrappingMode::MirroredRepeat => Wrap::MirroredRepeat,
        gltf::texture::WrappingMode::Repeat => Wrap::Repeat,
    }
}
