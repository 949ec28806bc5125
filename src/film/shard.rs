//! Shards: one machine's share of a sequence's frames or of a still's samples (`I/N`), and the
//! sample-shard EXR that keeps a still's exact per-pixel sums and weights so `glint merge` can add them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use glam::DVec4;

use super::{write_through_temp, EncodeError, FilmError, Image};

/// One machine's share: the items (frames, or sample indices) with `item % count == index`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: u32,
    pub count: u32,
}

impl Shard {
    /// Whether item `i` is this shard's.
    pub fn takes(&self, i: u32) -> bool {
        i % self.count == self.index
    }
}

impl FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (i, n) = s
            .split_once('/')
            .ok_or_else(|| format!("'{s}': expected I/N (e.g. 3/8)"))?;
        let parse = |v: &str, what: &str| {
            v.trim()
                .parse::<u32>()
                .map_err(|e| format!("'{s}': {what} '{v}': {e}"))
        };
        let (index, count) = (parse(i, "shard index")?, parse(n, "shard count")?);
        if count == 0 {
            return Err(format!("'{s}': the shard count must be at least 1"));
        }
        if index >= count {
            return Err(format!(
                "'{s}': the shard index must be below the count (0..={})",
                count - 1
            ));
        }
        Ok(Shard { index, count })
    }
}

/// A pixel's weighted sum of samples and the sum of their filter weights, as the render holds them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    pub sum: DVec4,
    pub weight: f64,
}

impl PixelSum {
    /// The pixel's value, computed as the render computes it (so equal sums give equal bits).
    pub fn value(&self) -> glam::Vec4 {
        if self.weight != 0.0 {
            (self.sum / self.weight).as_vec4()
        } else {
            glam::Vec4::ZERO
        }
    }
}

/// A sample shard of a still: which share, the settings it belongs to, and its pixels' sums.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleShard {
    pub shard: Shard,
    /// Hash of the scene and every setting that changes pixels (`settings_hash`).
    pub settings: u64,
    pub width: usize,
    pub height: usize,
    pub sums: Vec<PixelSum>,
}

#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error("no shards to merge")]
    Empty,
    #[error("{}: {error}", path.display())]
    Read {
        path: PathBuf,
        error: exr::error::Error,
    },
    #[error("{}: not a glint sample shard (no {what} in its header)", path.display())]
    NotAShard { path: PathBuf, what: &'static str },
    #[error("{}: channel {channel} is missing or not 32-bit unsigned", path.display())]
    Channel { path: PathBuf, channel: String },
    #[error("{}: shard {index}/{count} of settings {theirs:016x}, but {}: settings {ours:016x} (another scene or other settings)", path.display(), first.display())]
    OtherSettings {
        path: PathBuf,
        index: u32,
        count: u32,
        theirs: u64,
        first: PathBuf,
        ours: u64,
    },
    #[error("{}: shard of {theirs} shards ({w}x{h}), but {}: {ours} shards ({fw}x{fh})", path.display(), first.display())]
    OtherSplit {
        path: PathBuf,
        theirs: u32,
        w: usize,
        h: usize,
        first: PathBuf,
        ours: u32,
        fw: usize,
        fh: usize,
    },
    #[error("shard {index}/{count} given twice: {} and {}", a.display(), b.display())]
    Duplicate {
        index: u32,
        count: u32,
        a: PathBuf,
        b: PathBuf,
    },
    #[error("missing shards of {count}: {}", missing.iter().map(|i| format!("{i}/{count}")).collect::<Vec<_>>().join(", "))]
    Missing { count: u32, missing: Vec<u32> },
}

/// FNV-1a over the parts, each ended by a 0xff byte (stable across builds and machines, unlike
/// std's hasher, and with no two part lists alike).
pub fn settings_hash(parts: &[&[u8]]) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for part in parts {
        for &b in part.iter().chain(&[0xff]) {
            h = (h ^ b as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

const SETTINGS_ATTR: &str = "glintSettings";
const SHARD_ATTR: &str = "glintSampleShard";
/// Each f64 sum travels exactly as the two halves of its bits (EXR has no 64-bit samples).
const SUMS: [&str; 5] = ["sum.R", "sum.G", "sum.B", "sum.A", "weight"];

fn component(p: &PixelSum, k: usize) -> f64 {
    if k < 4 {
        p.sum[k]
    } else {
        p.weight
    }
}

/// Writes a sample shard: RGBA (this shard's own mean, to look at) and the exact sums, with the
/// shard and settings hash in the header; through a temporary file and a rename.
pub fn write_sample_shard(shard: &SampleShard, path: &Path) -> Result<(), FilmError> {
    write_through_temp(path, |tmp| encode(shard, tmp))
}

fn encode(shard: &SampleShard, path: &Path) -> Result<(), EncodeError> {
    use exr::prelude::*;
    let mean: Vec<glam::Vec4> = shard.sums.iter().map(PixelSum::value).collect();
    let mut channels: Vec<AnyChannel<FlatSamples>> = ["R", "G", "B", "A"]
        .iter()
        .enumerate()
        .map(|(k, name)| {
            AnyChannel::new(*name, FlatSamples::F32(mean.iter().map(|p| p[k]).collect()))
        })
        .collect();
    for (k, name) in SUMS.iter().enumerate() {
        let bits: Vec<u64> = shard
            .sums
            .iter()
            .map(|p| component(p, k).to_bits())
            .collect();
        let hi = bits.iter().map(|b| (b >> 32) as u32).collect();
        let lo = bits.iter().map(|&b| b as u32).collect();
        channels.push(AnyChannel::new(
            format!("{name}.hi").as_str(),
            FlatSamples::U32(hi),
        ));
        channels.push(AnyChannel::new(
            format!("{name}.lo").as_str(),
            FlatSamples::U32(lo),
        ));
    }
    let mut attrs = LayerAttributes::default();
    let s = shard.shard;
    attrs.other.insert(
        Text::from(SHARD_ATTR),
        AttributeValue::Text(Text::from(format!("{}/{}", s.index, s.count).as_str())),
    );
    attrs.other.insert(
        Text::from(SETTINGS_ATTR),
        AttributeValue::Text(Text::from(format!("{:016x}", shard.settings).as_str())),
    );
    let layer = Layer::new(
        (shard.width, shard.height),
        attrs,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels.into()),
    );
    Image::from_layer(layer)
        .write()
        .to_file(path)
        .map_err(EncodeError::Exr)
}

/// Reads a sample shard written by `write_sample_shard`.
pub fn read_sample_shard(path: &Path) -> Result<SampleShard, MergeError> {
    use exr::prelude::*;
    let read_err = |what| MergeError::NotAShard {
        path: path.to_path_buf(),
        what,
    };
    let image = super::layers::read_first_layer(path).map_err(|error| MergeError::Read {
        path: path.to_path_buf(),
        error,
    })?;
    let layer = &image.layer_data;
    let text = |key: &str| match layer.attributes.other.get(&Text::from(key)) {
        Some(AttributeValue::Text(t)) => Some(t.to_string()),
        _ => None,
    };
    let shard: Shard = text(SHARD_ATTR)
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| read_err(SHARD_ATTR))?;
    let settings = text(SETTINGS_ATTR)
        .and_then(|s| u64::from_str_radix(&s, 16).ok())
        .ok_or_else(|| read_err(SETTINGS_ATTR))?;
    let (width, height) = (layer.size.width(), layer.size.height());
    let channel = |name: String| {
        layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name.to_string() == name)
            .and_then(|c| match &c.sample_data {
                FlatSamples::U32(v) if v.len() == width * height => Some(v),
                _ => None,
            })
            .ok_or(MergeError::Channel {
                path: path.to_path_buf(),
                channel: name,
            })
    };
    let mut sums = vec![PixelSum::default(); width * height];
    for (k, name) in SUMS.iter().enumerate() {
        let (hi, lo) = (
            channel(format!("{name}.hi"))?,
            channel(format!("{name}.lo"))?,
        );
        for ((p, &h), &l) in sums.iter_mut().zip(hi).zip(lo) {
            let v = f64::from_bits(((h as u64) << 32) | l as u64);
            if k < 4 {
                p.sum[k] = v;
            } else {
                p.weight = v;
            }
        }
    }
    Ok(SampleShard {
        shard,
        settings,
        width,
        height,
        sums,
    })
}

/// Adds the shards (each of the same settings and split, every index once) into the image the
/// whole render gives; sums are added in shard order, whatever order the files come in.
pub fn merge(shards: &[(PathBuf, SampleShard)]) -> Result<Image, MergeError> {
    let (first_path, first) = shards.first().ok_or(MergeError::Empty)?;
    let count = first.shard.count;
    let mut by_index: BTreeMap<u32, &(PathBuf, SampleShard)> = BTreeMap::new();
    for entry in shards {
        let (path, s) = entry;
        if s.settings != first.settings {
            return Err(MergeError::OtherSettings {
                path: path.clone(),
                index: s.shard.index,
                count: s.shard.count,
                theirs: s.settings,
                first: first_path.clone(),
                ours: first.settings,
            });
        }
        if (s.shard.count, s.width, s.height) != (count, first.width, first.height) {
            return Err(MergeError::OtherSplit {
                path: path.clone(),
                theirs: s.shard.count,
                w: s.width,
                h: s.height,
                first: first_path.clone(),
                ours: count,
                fw: first.width,
                fh: first.height,
            });
        }
        if let Some((a, _)) = by_index.insert(s.shard.index, entry) {
            return Err(MergeError::Duplicate {
                index: s.shard.index,
                count,
                a: a.clone(),
                b: path.clone(),
            });
        }
    }
    let missing: Vec<u32> = (0..count).filter(|i| !by_index.contains_key(i)).collect();
    if !missing.is_empty() {
        return Err(MergeError::Missing { count, missing });
    }
    let mut total = vec![PixelSum::default(); first.width * first.height];
    for (_, s) in by_index.values() {
        for (t, p) in total.iter_mut().zip(&s.sums) {
            t.sum += p.sum;
            t.weight += p.weight;
        }
    }
    Ok(Image {
        width: first.width,
        height: first.height,
        pixels: total.iter().map(PixelSum::value).collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shard(index: u32, count: u32, settings: u64, v: f64) -> (PathBuf, SampleShard) {
        let sums = vec![
            PixelSum {
                sum: DVec4::splat(v),
                weight: 1.0,
            };
            2
        ];
        let s = SampleShard {
            shard: Shard { index, count },
            settings,
            width: 2,
            height: 1,
            sums,
        };
        (PathBuf::from(format!("part{index}.exr")), s)
    }

    #[test]
    fn shard_files_keep_the_sums_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let (_, mut s) = shard(2, 5, 0xdead_beef_0123_4567, 0.1);
        s.sums[1].sum = DVec4::new(1.0 / 3.0, 1e-300, -2.5e10, 1.0);
        s.sums[1].weight = std::f64::consts::PI;
        let p = dir.path().join("s.exr");
        write_sample_shard(&s, &p).unwrap();
        assert_eq!(read_sample_shard(&p).unwrap(), s);
    }

    #[test]
    fn merge_names_missing_duplicate_and_foreign_shards() {
        let err = merge(&[shard(0, 4, 1, 0.5), shard(2, 4, 1, 0.5)]).unwrap_err();
        assert_eq!(err.to_string(), "missing shards of 4: 1/4, 3/4");
        let err = merge(&[shard(0, 2, 1, 0.5), shard(0, 2, 1, 0.5)]).unwrap_err();
        assert!(err.to_string().contains("given twice"), "{err}");
        let err = merge(&[shard(0, 2, 1, 0.5), shard(1, 2, 9, 0.5)]).unwrap_err();
        assert!(err.to_string().contains("another scene"), "{err}");
        let err = merge(&[shard(0, 2, 1, 0.5), shard(1, 3, 1, 0.5)]).unwrap_err();
        assert!(err.to_string().contains("3 shards"), "{err}");
        let ok = merge(&[shard(1, 2, 1, 0.25), shard(0, 2, 1, 0.5)]).unwrap();
        assert_eq!(ok.pixels[0], glam::Vec4::splat(0.375));
    }

    #[test]
    fn settings_hash_separates_parts() {
        assert_ne!(settings_hash(&[b"ab", b"c"]), settings_hash(&[b"a", b"bc"]));
        assert_eq!(settings_hash(&[b"x"]), settings_hash(&[b"x"]));
    }
}
