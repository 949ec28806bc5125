//! Multi-layer EXR: the beauty as `R,G,B,A` and each feature image as named channels beside it in one
//! part (`albedo.R`, `N.X`, `Z`, ...), the layer.channel names compositors group; and reading one back.

use std::path::Path;

use glam::{Vec3, Vec4};

use super::{write_through_temp, EncodeError, FilmError, Image};

/// The values of one feature image, one per pixel, and how its channels are named.
#[derive(Clone, Copy, Debug)]
pub enum Values<'a> {
    /// `name.R`, `name.G`, `name.B`, `name.A` (the beauty itself when the name is empty).
    Rgba(&'a [Vec4]),
    /// `name.R`, `name.G`, `name.B`.
    Rgb(&'a [Vec3]),
    /// `name.X`, `name.Y`, `name.Z` (vectors and points).
    Xyz(&'a [Vec3]),
    /// One float channel named `name`.
    Scalar(&'a [f32]),
    /// One 32-bit unsigned channel named `name` (ids and counts, exact).
    Uint(&'a [u32]),
}

/// One named feature image of a multi-layer file.
#[derive(Clone, Copy, Debug)]
pub struct Layer<'a> {
    pub name: &'a str,
    pub values: Values<'a>,
}

type Channel = exr::prelude::AnyChannel<exr::prelude::FlatSamples>;

fn channels_of(layer: &Layer, out: &mut Vec<Channel>) {
    use exr::prelude::{AnyChannel, FlatSamples};
    let named = |suffix: &str| match (layer.name, suffix) {
        ("", s) => s.to_string(),
        (n, "") => n.to_string(),
        (n, s) => format!("{n}.{s}"),
    };
    let mut floats = |names: &[&str], get: &dyn Fn(usize, usize) -> f32, n: usize| {
        for (k, s) in names.iter().enumerate() {
            let v = (0..n).map(|i| get(i, k)).collect();
            out.push(AnyChannel::new(named(s).as_str(), FlatSamples::F32(v)));
        }
    };
    match layer.values {
        Values::Rgba(v) => floats(&["R", "G", "B", "A"], &|i, k| v[i][k], v.len()),
        Values::Rgb(v) => floats(&["R", "G", "B"], &|i, k| v[i][k], v.len()),
        Values::Xyz(v) => floats(&["X", "Y", "Z"], &|i, k| v[i][k], v.len()),
        Values::Scalar(v) => floats(&[""], &|i, _| v[i], v.len()),
        Values::Uint(v) => out.push(AnyChannel::new(
            named("").as_str(),
            FlatSamples::U32(v.to_vec()),
        )),
    }
}

/// Writes `beauty` and `layers` (each with a value per pixel) into one EXR, through a temporary file.
pub fn write_layers(beauty: &Image, layers: &[Layer], path: &Path) -> Result<(), FilmError> {
    use exr::prelude::{AnyChannels, Encoding, Image as ExrImage, LayerAttributes, WritableImage};
    let n = beauty.width * beauty.height;
    let mut channels = Vec::new();
    channels_of(
        &Layer {
            name: "",
            values: Values::Rgba(&beauty.pixels),
        },
        &mut channels,
    );
    for l in layers {
        channels_of(l, &mut channels);
    }
    assert!(
        channels.iter().all(|c| c.sample_data.len() == n),
        "every feature image has a value per pixel"
    );
    let layer = exr::prelude::Layer::new(
        (beauty.width, beauty.height),
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    write_through_temp(path, |tmp| {
        // Blocks in file order: the same images give the same bytes.
        ExrImage::from_layer(layer)
            .write()
            .non_parallel()
            .to_file(tmp)
            .map_err(EncodeError::Exr)
    })
}

/// An EXR's first valid layer with every channel and attribute, as sample shards and channel
/// readers want it.
pub(super) type FirstLayer =
    exr::prelude::Image<exr::prelude::Layer<exr::prelude::AnyChannels<exr::prelude::FlatSamples>>>;

/// Reads an EXR's first valid layer, whole (its largest resolution level).
pub(super) fn read_first_layer(path: &Path) -> Result<FirstLayer, exr::error::Error> {
    use exr::prelude::*;
    read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
}

/// One channel of an EXR's first layer, as floats (u32 channels converted), by its full name.
pub fn read_channel(path: &Path, name: &str) -> Result<Option<Vec<f32>>, FilmError> {
    let image = read_first_layer(path).map_err(|error| FilmError::ReadExr {
        path: path.to_path_buf(),
        error,
    })?;
    Ok(image
        .layer_data
        .channel_data
        .list
        .iter()
        .find(|c| c.name.to_string() == name)
        .map(|c| c.sample_data.values_as_f32().collect()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layers_round_trip_under_their_names() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("l.exr");
        let mut beauty = Image::new(2, 1);
        beauty.pixels[1] = Vec4::new(1.0, 2.0, 3.0, 0.5);
        let albedo = [Vec3::new(0.1, 0.2, 0.3), Vec3::ONE];
        let z = [4.0, f32::INFINITY];
        let ids = [7u32, u32::MAX];
        let layers = [
            ("albedo", Values::Rgb(&albedo)),
            ("N", Values::Xyz(&albedo)),
            ("Z", Values::Scalar(&z)),
            ("instance.id", Values::Uint(&ids)),
        ]
        .map(|(name, values)| Layer { name, values });
        write_layers(&beauty, &layers, &path).unwrap();
        let ch = |n: &str| read_channel(&path, n).unwrap().unwrap();
        assert_eq!(ch("B"), [0.0, 3.0]);
        assert_eq!(ch("A"), [0.0, 0.5]);
        assert_eq!(ch("albedo.G"), [0.2, 1.0]);
        assert_eq!(ch("N.Z"), [0.3, 1.0]);
        assert_eq!(ch("Z"), z);
        assert_eq!(ch("instance.id"), [7.0, u32::MAX as f32]);
        assert!(read_channel(&path, "P.X").unwrap().is_none());
        // The beauty reads back as the RGBA image it was.
        assert_eq!(super::super::read_exr(&path).unwrap(), beauty);
    }
}
