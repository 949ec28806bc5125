//! Textures as 8-bit RGBA images with glTF's wrap modes, sampled bilinearly (or by nearest texel)
//! into linear colour. sRGB textures (base colour, emission) are decoded through a table; data
//! textures stay linear.

use std::sync::OnceLock;

use glam::{Vec2, Vec4};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wrap {
    Repeat,
    ClampToEdge,
    MirroredRepeat,
}

/// `i` modulo `n` (> 0) in `0..n`, as `rem_euclid`, without its integer division where `i` is
/// within a period of the range, as texel coordinates nearly always are (textures' repeats, and
/// environment maps' columns, where it was measured).
#[inline]
pub(crate) fn wrap_index(i: i64, n: i64) -> i64 {
    if (0..n).contains(&i) {
        i
    } else if (n..2 * n).contains(&i) {
        i - n
    } else if (-n..0).contains(&i) {
        i + n
    } else {
        i.rem_euclid(n)
    }
}

impl Wrap {
    /// Maps an integer texel coordinate into `0..n`.
    fn index(self, i: i64, n: usize) -> usize {
        let n = n as i64;
        let k = match self {
            Wrap::Repeat => wrap_index(i, n),
            Wrap::ClampToEdge => i.clamp(0, n - 1),
            Wrap::MirroredRepeat => {
                let m = wrap_index(i, 2 * n);
                if m < n {
                    m
                } else {
                    2 * n - 1 - m
                }
            }
        };
        k as usize
    }
}

/// How a lookup between texel centres is filtered. There are no mip levels (pixel-area sampling
/// averages minified texels), so one filter serves magnification and minification.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TextureFilter {
    #[default]
    Linear,
    /// The texel holding the point: pixel art, lookup tables and ID maps stay crisp.
    Nearest,
}

#[derive(Clone, Debug)]
pub struct Texture {
    pub name: String,
    pub width: usize,
    pub height: usize,
    /// Row-major RGBA8, first row at the top (v = 0), as glTF defines.
    pub pixels: Vec<[u8; 4]>,
    /// Whether RGB is sRGB-encoded (alpha is always linear).
    pub srgb: bool,
    pub wrap_s: Wrap,
    pub wrap_t: Wrap,
    pub filter: TextureFilter,
}

fn srgb_table() -> &'static [f32; 256] {
    static TABLE: OnceLock<[f32; 256]> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [0.0; 256];
        for (i, v) in t.iter_mut().enumerate() {
            *v = crate::geometry::colour::srgb_to_linear(i as f32 / 255.0);
        }
        t
    })
}

impl Texture {
    /// A texture with glTF's default sampler (repeating both ways, filtered linearly), as OBJ's
    /// textures and the ones glint derives have.
    pub fn repeating(
        name: String,
        (width, height): (usize, usize),
        pixels: Vec<[u8; 4]>,
        srgb: bool,
    ) -> Self {
        Self {
            name,
            width,
            height,
            pixels,
            srgb,
            wrap_s: Wrap::Repeat,
            wrap_t: Wrap::Repeat,
            filter: TextureFilter::Linear,
        }
    }

    fn texel(&self, x: usize, y: usize) -> Vec4 {
        let p = self.pixels[y * self.width + x];
        let a = p[3] as f32 / 255.0;
        if self.srgb {
            let t = srgb_table();
            Vec4::new(t[p[0] as usize], t[p[1] as usize], t[p[2] as usize], a)
        } else {
            Vec4::new(p[0] as f32, p[1] as f32, p[2] as f32, p[3] as f32) / 255.0
        }
    }

    /// Lookup at `uv` (texel centres at half-integers) through the texture's filter, honouring
    /// the wrap modes.
    pub fn sample(&self, uv: Vec2) -> Vec4 {
        if self.width == 0 || self.height == 0 || !uv.is_finite() {
            return Vec4::ONE;
        }
        if self.filter == TextureFilter::Nearest {
            // Floats beyond i64 saturate in the cast, and every wrap maps those into range.
            let x = (uv.x * self.width as f32).floor() as i64;
            let y = (uv.y * self.height as f32).floor() as i64;
            return self.texel(
                self.wrap_s.index(x, self.width),
                self.wrap_t.index(y, self.height),
            );
        }
        let x = uv.x * self.width as f32 - 0.5;
        let y = uv.y * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let xs = [
            self.wrap_s.index(x0, self.width),
            self.wrap_s.index(x0.saturating_add(1), self.width),
        ];
        let ys = [
            self.wrap_t.index(y0, self.height),
            self.wrap_t.index(y0.saturating_add(1), self.height),
        ];
        let top = self.texel(xs[0], ys[0]).lerp(self.texel(xs[1], ys[0]), fx);
        let bottom = self.texel(xs[0], ys[1]).lerp(self.texel(xs[1], ys[1]), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker(wrap: Wrap) -> Texture {
        Texture {
            name: "t".into(),
            width: 2,
            height: 1,
            pixels: vec![[0, 0, 0, 255], [255, 255, 255, 255]],
            srgb: false,
            wrap_s: wrap,
            wrap_t: wrap,
            filter: TextureFilter::Linear,
        }
    }

    #[test]
    fn nearest_takes_the_texel_holding_the_point() {
        let t = Texture {
            filter: TextureFilter::Nearest,
            ..checker(Wrap::Repeat)
        };
        // Linear would give 0.5 at the border between the two texels and 0.25 a quarter before.
        assert_eq!(t.sample(Vec2::new(0.49, 0.5)).x, 0.0);
        assert_eq!(t.sample(Vec2::new(0.5, 0.5)).x, 1.0);
        assert_eq!(t.sample(Vec2::new(0.99, 0.5)).x, 1.0);
        // Wrapped: u = 1.25 is texel 0 again, u = -0.25 texel 1.
        assert_eq!(t.sample(Vec2::new(1.25, 0.5)).x, 0.0);
        assert_eq!(t.sample(Vec2::new(-0.25, 0.5)).x, 1.0);
        for u in [1e30, -1e30] {
            let v = t.sample(Vec2::new(u, 0.5)).x;
            assert!(v == 0.0 || v == 1.0, "at {u}: {v}");
        }
    }

    #[test]
    fn texel_centres_are_exact_and_between_is_linear() {
        let t = checker(Wrap::ClampToEdge);
        assert_eq!(t.sample(Vec2::new(0.25, 0.5)).x, 0.0);
        assert_eq!(t.sample(Vec2::new(0.75, 0.5)).x, 1.0);
        assert!((t.sample(Vec2::new(0.5, 0.5)).x - 0.5).abs() < 1e-6);
    }

    #[test]
    fn wrap_modes_differ_past_the_edge() {
        // At u = 1.0 the lookup falls between the last texel and the one past the edge.
        let u = Vec2::new(1.0, 0.5);
        assert!((checker(Wrap::Repeat).sample(u).x - 0.5).abs() < 1e-6);
        assert_eq!(checker(Wrap::ClampToEdge).sample(u).x, 1.0);
        assert_eq!(checker(Wrap::MirroredRepeat).sample(u).x, 1.0);
        assert_eq!(Wrap::MirroredRepeat.index(-1, 4), 0);
        for n in [1i64, 3, 4, 2048] {
            for i in [
                -5 * n - 1,
                -n - 1,
                -n,
                -1,
                0,
                1,
                n - 1,
                n,
                2 * n - 1,
                2 * n,
                7 * n + 2,
            ] {
                assert_eq!(wrap_index(i, n), i.rem_euclid(n), "{i} mod {n}");
            }
        }
        assert_eq!(wrap_index(i64::MIN, 5), i64::MIN.rem_euclid(5));
        assert_eq!(Wrap::MirroredRepeat.index(4, 4), 3);
        assert_eq!(Wrap::Repeat.index(-1, 4), 3);
    }

    #[test]
    fn coordinates_beyond_i64_clamp_to_an_edge_texel_in_every_wrap_mode() {
        // A fuzzed UV of 1e30 floors to i64::MAX, whose right neighbour overflowed.
        for wrap in [Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat] {
            for u in [1e30, -1e30] {
                let v = checker(wrap).sample(Vec2::new(u, 0.5)).x;
                assert!(v == 0.0 || v == 1.0, "{wrap:?} at {u}: {v}");
            }
        }
    }
}
