//! The BasisLZ supercompression global data of an ETC1S KTX2 file: its header, the image
//! descriptors and the codebooks, every length checked against the section that holds it.

use glint_basisu::{Etc1sCodebooks, Etc1sSlices};

use super::Ktx2Error;

/// The parsed global data: codebook byte ranges and image descriptors, all inside `data`.
pub(super) struct GlobalData<'a> {
    endpoint_count: u32,
    selector_count: u32,
    endpoints: &'a [u8],
    selectors: &'a [u8],
    tables: &'a [u8],
    /// (flags, rgb offset, rgb length, alpha offset, alpha length) of the first image.
    first: [u32; 5],
}

const HEADER: usize = 20;
const IMAGE_DESC: usize = 20;

fn u32_at(d: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([d[at], d[at + 1], d[at + 2], d[at + 3]])
}

impl<'a> GlobalData<'a> {
    /// Parses the section of a file with `levels` levels and `layers` layers of one face each.
    pub(super) fn parse(data: &'a [u8], levels: u32, layers: u32) -> Result<Self, Ktx2Error> {
        let err = Ktx2Error::BasisLz;
        if data.len() < HEADER {
            return Err(err("shorter than its header"));
        }
        let endpoint_count = u16::from_le_bytes([data[0], data[1]]) as u32;
        let selector_count = u16::from_le_bytes([data[2], data[3]]) as u32;
        let lens = [
            u32_at(data, 4),
            u32_at(data, 8),
            u32_at(data, 12),
            u32_at(data, 16),
        ];
        let images = levels as u64 * layers as u64;
        let descs = images * IMAGE_DESC as u64;
        let total = HEADER as u64 + descs + lens.iter().map(|&l| l as u64).sum::<u64>();
        if total > data.len() as u64 {
            return Err(err("its image descriptors and codebooks overrun it"));
        }
        if endpoint_count == 0 || selector_count == 0 {
            return Err(err("no endpoints or selectors"));
        }
        let mut at = HEADER + descs as usize;
        let mut take = |len: u32| {
            let s = &data[at..at + len as usize];
            at += len as usize;
            s
        };
        let (endpoints, selectors, tables) = (take(lens[0]), take(lens[1]), take(lens[2]));
        let d = &data[HEADER..HEADER + IMAGE_DESC];
        let first = [0, 4, 8, 12, 16].map(|o| u32_at(d, o));
        Ok(Self {
            endpoint_count,
            selector_count,
            endpoints,
            selectors,
            tables,
            first,
        })
    }

    pub(super) fn codebooks(&self) -> Etc1sCodebooks<'a> {
        Etc1sCodebooks {
            endpoints: self.endpoints,
            num_endpoints: self.endpoint_count,
            selectors: self.selectors,
            num_selectors: self.selector_count,
            tables: self.tables,
        }
    }

    /// The first image's slices, checked against its level's `level_len` bytes.
    pub(super) fn first_image_slices(&self, level_len: usize) -> Result<Etc1sSlices, Ktx2Error> {
        let [_, rgb_off, rgb_len, alpha_off, alpha_len] = self.first;
        let fits = |o: u32, l: u32| o as u64 + l as u64 <= level_len as u64;
        if rgb_len == 0 || !fits(rgb_off, rgb_len) || !fits(alpha_off, alpha_len) {
            return Err(Ktx2Error::BasisLz(
                "the first image's slices lie outside its level",
            ));
        }
        Ok(Etc1sSlices {
            rgb: (rgb_off, rgb_len),
            alpha: (alpha_off, alpha_len),
        })
    }
}
