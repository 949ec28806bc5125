//! The glTF metallic-roughness base (spec appendix B, KHR_materials_transmission/ior/volume/specular):
//! Lambert, GGX/Smith reflection and transmission (Walter et al. 2007, visible normals after Heitz
//! 2018), and delta lobes for smooth mirrors and glass, chosen among by their rough weights.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::diffuse_transmission::DiffuseTransmission;
use super::energy;
use super::fresnel::{fresnel_exact, schlick};
use super::layer_albedo;
use super::microfacet::Ggx;
use super::{choice_probabilities, luminance, Bsdf, BsdfSample};
use crate::sample::warp::cosine_hemisphere;
use crate::scene::{GgxScattering, Layering};

/// Probabilities of the three lobes (reflection, diffuse, transmission).
#[derive(Clone, Copy, Debug)]
pub(super) struct Lobes {
    pub reflect: f32,
    pub diffuse: f32,
    pub transmit: f32,
}

impl Bsdf {
    /// Whether every lobe of the base is a delta lobe.
    pub(super) fn base_is_delta(&self) -> bool {
        self.alpha == 0.0 && (self.metallic == 1.0 || self.transmission == 1.0)
    }

    /// The specular lobes' microfacet distribution (anisotropic along the frame's tangent when
    /// `alpha_t` differs from `alpha`).
    pub(super) fn ggx(&self) -> Ggx {
        Ggx {
            ax: self.alpha_t,
            ay: self.alpha,
        }
    }

    /// The diffuse lobe's choice probability where the base is Lambert alone (no specular layer,
    /// metal, transmission or thin film; and from this side no total internal reflection can turn
    /// the zero-weight layer into a mirror), else None. Every other term is then exactly zero, so
    /// eval and sample skip the Fresnel and microfacet work they would multiply by it, and give
    /// the same bits (walls of OBJ scenes are mostly this).
    pub(super) fn lambert_only(&self) -> Option<f32> {
        let w = luminance(self.base);
        (self.plain() && w > 0.0).then(|| choice_probabilities([0.0, w, 0.0])[1])
    }

    /// The base is Lambert alone or nothing: no specular layer, metal, transmission or thin film,
    /// and from this side no total internal reflection.
    fn plain(&self) -> bool {
        self.specular == 0.0
            && self.metallic == 0.0
            && self.transmission == 0.0
            && self.eta >= 1.0
            && self.diffuse_transmission.is_none()
            && self.iridescence.is_none()
    }

    /// Whether the surface scatters no light at all: a plain black base under no coat or sheen
    /// (glTF emitters often are), where `eval` is zero everywhere and `sample` brings nothing.
    pub fn scatters_nothing(&self) -> bool {
        self.plain() && self.base == Vec3::ZERO && self.coat.is_none() && self.sheen.is_none()
    }

    /// A thick surface between equal indices: rough or not, it refracts nothing (the microfacet
    /// half vector of Walter et al. degenerates there), so its transmission is a straight delta.
    fn index_matched(&self) -> bool {
        !self.thin && (self.eta - 1.0).abs() < 1e-3
    }

    /// Whether the rough reflection and transmission lobes are chosen between at the sampled
    /// microfacet (pbrt-v4's dielectric does this): both exist and are rough.
    fn splits_at_microfacet(&self) -> bool {
        self.alpha > 0.0 && self.transmits() && !self.index_matched()
    }

    /// Where `splits_at_microfacet`, the probability of reflecting rather than transmitting at a
    /// microfacet of cosine `oh` with the view: each side's weight there, so a microfacet that
    /// reflects totally always reflects. The macro surface's Fresnel, which chose between them
    /// before, sent samples inside a rough sphere to refract where the microfacet reflects
    /// totally, and those samples ended. TransmissionRoughnessTest under a uniform white map, 64
    /// spp x 2 seeds: sigma 0.131 -> 0.092 (Cycles 0.101), mean the same; under a sky, 6 seeds,
    /// past the 20 worst pixels 0.303 -> 0.286; 2-10% more time a sample (the paths go on).
    /// `fresnel` and `through` are the microfacet's `Bsdf::fresnel` and the dielectric's 1 - F
    /// (`dielectric_through`), which the callers have computed for the lobes' values.
    fn reflect_share(&self, fresnel: Vec3, through: f32) -> f32 {
        let r = luminance(fresnel);
        let t = (1.0 - self.metallic) * through * self.transmission * luminance(self.base);
        if r + t > 0.0 {
            r / (r + t)
        } else {
            1.0
        }
    }

    /// Fresnel reflectance of the dielectric layer (exact, scaled by the specular weight; total
    /// internal reflection reflects everything whatever the weight); with a specular colour, its
    /// strongest channel, which is what the layers below lose.
    fn fresnel_dielectric(&self, cos: f32) -> f32 {
        self.dielectric_reflectance(cos).0
    }

    /// `fresnel_dielectric` and, with a thin film (KHR_materials_iridescence, mixed in by its
    /// factor), the layer's reflectance per channel, from one evaluation of the film.
    fn dielectric_reflectance(&self, cos: f32) -> (f32, Option<Vec3>) {
        let plain = self.plain_fresnel_dielectric(cos);
        if plain >= 1.0 {
            return (1.0, self.iridescence.as_ref().map(|_| Vec3::ONE));
        }
        let Some(film) = &self.iridescence else {
            return (plain, None);
        };
        let thin = self.specular * film.fresnel(cos, self.dielectric_f0());
        let scalar = plain + (thin.max_element() - plain) * film.factor;
        (scalar, Some(Vec3::splat(plain).lerp(thin, film.factor)))
    }

    /// What the dielectric layer lets through to the layers below at `cos`: the scalar `1 - F` the
    /// lobes are weighted by and, with a thin film, each channel's share relative to it. The film
    /// absorbs nothing, so what it does not reflect of each channel goes on: `1 - F_rgb` with the
    /// film's own colours, as the spec's fresnel_mix with the extension's RGB Fresnel and Cycles'
    /// thin film do (the specular colour's share stays KHR_materials_specular's strongest channel).
    fn dielectric_through(&self, cos: f32) -> (f32, Option<Vec3>) {
        let (f, rgb) = self.dielectric_reflectance(cos);
        let t = 1.0 - f;
        let share = rgb.map(|rgb| {
            if t <= 0.0 {
                Vec3::ZERO
            } else {
                (Vec3::ONE - rgb).max(Vec3::ZERO) / t
            }
        });
        (t, share)
    }

    /// `fresnel_dielectric` without the film: 1 under total internal reflection.
    fn plain_fresnel_dielectric(&self, cos: f32) -> f32 {
        self.specular_share(fresnel_exact(cos, self.eta))
    }

    /// The layer's reflectance for an untinted Fresnel `f`: scaled by the specular weight, tinted
    /// by the specular colour (its strongest channel), and 1 under total internal reflection.
    fn specular_share(&self, f: f32) -> f32 {
        if f >= 1.0 {
            1.0
        } else if self.specular_color == Vec3::ONE {
            self.specular * f
        } else {
            self.specular * self.tinted(f).max_element()
        }
    }

    /// The dielectric's normal-incidence reflectance per channel, tinted by the specular colour.
    fn dielectric_f0(&self) -> Vec3 {
        (fresnel_exact(1.0, self.eta) * self.specular_color).min(Vec3::ONE)
    }

    /// KHR_materials_specular's colour on the exact Fresnel: F0 tinted (and clamped to 1), and the
    /// rise to 1 at grazing incidence kept, as the spec's Schlick form does.
    fn tinted(&self, f: f32) -> Vec3 {
        let f0 = fresnel_exact(1.0, self.eta);
        let f0c = (f0 * self.specular_color).min(Vec3::ONE);
        let rise = ((f - f0) / (1.0 - f0)).clamp(0.0, 1.0);
        f0c + (Vec3::ONE - f0c) * rise
    }

    /// The dielectric layer's reflectance per channel.
    fn fresnel_dielectric_rgb(&self, cos: f32) -> Vec3 {
        let f = fresnel_exact(cos, self.eta);
        let plain = if f >= 1.0 {
            return Vec3::ONE;
        } else if self.specular_color == Vec3::ONE {
            Vec3::splat(self.specular * f)
        } else {
            self.specular * self.tinted(f)
        };
        match &self.iridescence {
            None => plain,
            Some(film) => plain.lerp(
                self.specular * film.fresnel(cos, self.dielectric_f0()),
                film.factor,
            ),
        }
    }

    /// Fresnel of the whole specular lobe: the dielectric and metal layers mixed by metalness; a
    /// thin film (KHR_materials_iridescence) mixes its reflectance into both by its factor.
    fn fresnel(&self, cos: f32) -> Vec3 {
        let mut metal = schlick(self.base, cos);
        if let Some(film) = &self.iridescence {
            metal = metal.lerp(film.fresnel(cos, self.base), film.factor);
        }
        self.fresnel_dielectric_rgb(cos).lerp(metal, self.metallic)
    }

    /// What the dielectric specular layer leaves the diffuse under it, at view cosine `cos_o` and
    /// microfacet cosine `oh`: 1 - F(V.H) (the spec's fresnel_mix, with a film's share per channel
    /// as `dielectric_through` gives it), or 1 - E(N.V) (albedo scaling, E estimated as Cycles
    /// does, from the Fresnel over the rough lobe's visible normals at N.V, times the
    /// multiple-scattering share; with a thin film, or seen from the denser side, the Fresnel at
    /// N.V, as Cycles falls back to; as Cycles' layering, the strongest channel of a film's
    /// albedo, so that no channel gains energy).
    fn diffuse_share(&self, cos_o: f32, oh: f32) -> (f32, Option<Vec3>) {
        match self.model.layering {
            Layering::Spec => self.dielectric_through(oh),
            Layering::Albedo => {
                let mut e = if self.alpha > 0.0 && self.eta > 1.0 && self.iridescence.is_none() {
                    self.specular_share(layer_albedo::estimate(&self.ggx(), cos_o, self.eta))
                } else {
                    self.fresnel_dielectric(cos_o)
                };
                if self.model.ggx == GgxScattering::Multi && self.alpha > 0.0 {
                    let fss = self.specular * energy::dielectric_average(self.eta);
                    e *= energy::darkening(&self.ggx(), cos_o, fss);
                }
                ((1.0 - e).max(0.0), None)
            }
        }
    }

    /// Multiple-scattering factor of the reflection lobe at view cosine `cos_o` (1 under the spec's
    /// single scattering): the dielectric and metal Fresnel averages mixed by metalness.
    fn reflection_compensation(&self, cos_o: f32) -> Vec3 {
        if self.model.ggx == GgxScattering::Single {
            return Vec3::ONE;
        }
        let f_avg = energy::dielectric_average(self.eta);
        let dielectric = if self.specular_color == Vec3::ONE {
            Vec3::splat(self.specular * f_avg)
        } else {
            self.specular * self.tinted(f_avg)
        };
        let fss = dielectric.lerp(energy::schlick_average(self.base), self.metallic);
        energy::compensation(&self.ggx(), cos_o, fss)
    }

    /// The base's rough lobe weights at `wo` (reflection, diffuse, transmission).
    fn lobe_weights(&self, cos_o: f32) -> [f32; 3] {
        let mut fd = self.fresnel_dielectric(cos_o);
        if self.alpha > 0.0 {
            // Rough microfacets still refract where the macro surface reflects totally.
            fd = fd.min(0.95);
        }
        let under = (1.0 - self.metallic) * (1.0 - fd) * luminance(self.base);
        let diffuse = match &self.diffuse_transmission {
            None => under * (1.0 - self.transmission),
            // The diffuse lobe also carries the transmitted colour, whatever the base colour.
            Some(dt) => {
                (1.0 - self.metallic)
                    * (1.0 - fd)
                    * (1.0 - self.transmission)
                    * dt.weight(self.base)
            }
        };
        [
            luminance(self.fresnel(cos_o)),
            diffuse,
            under * self.transmission,
        ]
    }

    /// An estimate of the base's albedo at `wo`, for choosing between layers.
    pub(super) fn base_estimate(&self, cos_o: f32) -> f32 {
        self.lobe_weights(cos_o).iter().sum()
    }

    /// Lobe choice probabilities at `wo`, from the lobes' rough weights, mixed with a little of a
    /// uniform choice so that no active lobe is starved.
    pub(super) fn lobes(&self, cos_o: f32) -> Lobes {
        let w = self.lobe_weights(cos_o);
        if w.iter().sum::<f32>() <= 0.0 {
            return Lobes {
                reflect: 1.0,
                diffuse: 0.0,
                transmit: 0.0,
            };
        }
        let [reflect, diffuse, transmit] = choice_probabilities(w);
        Lobes {
            reflect,
            diffuse,
            transmit,
        }
    }

    /// Value and pdf of the non-delta lobes for local directions `o` (above) and `i`.
    pub(super) fn base_eval(&self, o: Vec3, i: Vec3) -> (Vec3, f32) {
        if o.z <= 0.0 || i.z == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        match self.lambert_only() {
            Some(p) if i.z > 0.0 => (self.base * FRAC_1_PI, p * i.z * FRAC_1_PI),
            Some(_) => (Vec3::ZERO, 0.0),
            None => self.lobe_mix_eval(o, i),
        }
    }

    /// `base_eval` through the whole lobe mix (for `o` above and `i` off the surface).
    pub(super) fn lobe_mix_eval(&self, o: Vec3, i: Vec3) -> (Vec3, f32) {
        let lobes = self.lobes(o.z);
        let smooth = self.alpha == 0.0;
        let ggx = self.ggx();
        if i.z > 0.0 {
            let h = (o + i).normalize();
            let oh = o.dot(h).max(0.0);
            let (share, film) = self.diffuse_share(o.z, oh);
            let mut diffuse =
                self.base * ((1.0 - self.metallic) * (1.0 - self.transmission) * share * FRAC_1_PI);
            if let Some(film) = film {
                diffuse *= film;
            }
            let mut f = diffuse;
            let mut pdf = lobes.diffuse * i.z * FRAC_1_PI;
            if let Some(dt) = &self.diffuse_transmission {
                f = diffuse * (1.0 - dt.factor);
                pdf = lobes.diffuse * dt.pdf(dt.through_probability(self.base), i);
            }
            if !smooth {
                let d = ggx.d(h);
                let fresnel = self.fresnel(oh);
                f += fresnel
                    * self.reflection_compensation(o.z)
                    * (d * ggx.g2(o, i) / (4.0 * o.z * i.z));
                let chosen = if self.splits_at_microfacet() {
                    let through = self.dielectric_through(oh).0;
                    (lobes.reflect + lobes.transmit) * self.reflect_share(fresnel, through)
                } else {
                    lobes.reflect
                };
                pdf += chosen * ggx.g1(o) * d / (4.0 * o.z);
            }
            return (f, pdf);
        }
        let (f, pdf) = self.specular_btdf(o, i, &lobes);
        match &self.diffuse_transmission {
            None => (f, pdf),
            Some(dt) => {
                let (fd, pd) = self.diffuse_btdf(dt, o, i, &lobes);
                (f + fd, pdf + pd)
            }
        }
    }

    /// KHR_materials_diffuse_transmission's BTDF below the specular layer, which takes its Fresnel
    /// share at the half vector of `o` and `i` mirrored up (as for the thin specular BTDF), and its
    /// pdf within the diffuse lobe.
    fn diffuse_btdf(
        &self,
        dt: &DiffuseTransmission,
        o: Vec3,
        i: Vec3,
        lobes: &Lobes,
    ) -> (Vec3, f32) {
        let h = (o + Vec3::new(i.x, i.y, -i.z)).normalize();
        let (share, film) = self.diffuse_share(o.z, o.dot(h).max(0.0));
        let weight = (1.0 - self.metallic) * (1.0 - self.transmission) * share;
        let mut f = dt.eval(self.base, i) * weight;
        if let Some(film) = film {
            f *= film;
        }
        (
            f,
            lobes.diffuse * dt.pdf(dt.through_probability(self.base), i),
        )
    }

    /// Value and pdf of the specular transmission lobe (KHR_materials_transmission) for local `o`
    /// above and `i` below the surface.
    fn specular_btdf(&self, o: Vec3, i: Vec3, lobes: &Lobes) -> (Vec3, f32) {
        let smooth = self.alpha == 0.0;
        let ggx = self.ggx();
        if smooth || !self.transmits() || self.index_matched() {
            return (Vec3::ZERO, 0.0);
        }
        let tint = self.base * ((1.0 - self.metallic) * self.transmission);
        if self.thin {
            // The reflection lobe mirrored through the surface (the spec's H_T = V + L mirrored).
            let m = Vec3::new(i.x, i.y, -i.z);
            let h = (o + m).normalize();
            let d = ggx.d(h);
            let oh = o.dot(h).max(0.0);
            let (t, film) = self.dielectric_through(oh);
            let mut f = tint * (t * d * ggx.g2(o, m) / (4.0 * o.z * m.z));
            if let Some(film) = film {
                f *= film;
            }
            let pdf = self.transmit_choice(lobes, oh, t) * ggx.g1(o) * d / (4.0 * o.z);
            return (f, pdf);
        }
        // Rough dielectric refraction (Walter et al. 2007) as KHR_materials_volume writes it, with
        // ior_o^2 over the camera side's: no 1 / eta^2 radiance scaling, which the spec (and Cycles)
        // leave out, so a path that refracts once and leaves a volume through an open boundary (or
        // meets light inside it) keeps what it carried.
        let eta = self.eta;
        let mut h = (o + i * eta).normalize_or_zero();
        if h.z < 0.0 {
            h = -h;
        }
        let (oh, ih) = (o.dot(h), i.dot(h));
        if h == Vec3::ZERO || oh <= 0.0 || ih >= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let denom = (ih + oh / eta) * (ih + oh / eta);
        let d = ggx.d(h);
        let (t, film) = self.dielectric_through(oh);
        let mut f = tint * (t * d * ggx.g2(o, i) * (ih * oh).abs() / (denom * o.z * i.z.abs()));
        if let Some(film) = film {
            f *= film;
        }
        let pdf = self.transmit_choice(lobes, oh, t) * ggx.g1(o) * d * oh / o.z * ih.abs() / denom;
        (f, pdf)
    }

    /// The probability of choosing the rough transmission lobe at a microfacet of cosine `oh`,
    /// through which the dielectric passes `through`.
    fn transmit_choice(&self, lobes: &Lobes, oh: f32, through: f32) -> f32 {
        (lobes.reflect + lobes.transmit) * (1.0 - self.reflect_share(self.fresnel(oh), through))
    }

    /// Samples a direction: the reflection and transmission lobes through visible normals (or as
    /// delta lobes when smooth), the diffuse lobe by cosine.
    pub(super) fn base_sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let o = self.frame.to_local(wo);
        if o.z <= 0.0 {
            return None;
        }
        // Lambert alone: the diffuse lobe, unless u_lobe falls past its probability's rounding.
        let Some(p) = self.lambert_only().filter(|&p| u_lobe < p) else {
            return self.lobe_mix_sample(o, u_lobe, u);
        };
        let i = cosine_hemisphere(u);
        let (f, pdf) = (self.base * FRAC_1_PI, p * i.z * FRAC_1_PI);
        (i.z != 0.0 && pdf > 0.0 && f != Vec3::ZERO).then(|| BsdfSample {
            wi: self.frame.to_world(i),
            f,
            pdf,
            delta: false,
            straight: false,
        })
    }

    /// `base_sample` through the whole lobe mix (for local `o` above the surface).
    pub(super) fn lobe_mix_sample(&self, o: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let lobes = self.lobes(o.z);
        let smooth = self.alpha == 0.0;
        let ggx = self.ggx();
        let pick_reflect = u_lobe < lobes.reflect;
        let pick_transmit = !pick_reflect && u_lobe >= lobes.reflect + lobes.diffuse;
        let out = |i: Vec3, f: Vec3, pdf: f32, delta: bool, straight: bool| {
            (pdf > 0.0 && f != Vec3::ZERO).then(|| BsdfSample {
                wi: self.frame.to_world(i),
                f,
                pdf,
                delta,
                straight,
            })
        };
        if smooth && pick_reflect {
            let i = Vec3::new(-o.x, -o.y, o.z);
            return out(i, self.fresnel(o.z) / o.z, lobes.reflect, true, false);
        }
        if (smooth || self.index_matched()) && pick_transmit {
            let mut tint = self.base * ((1.0 - self.metallic) * self.transmission);
            let (t, film) = self.dielectric_through(o.z);
            if let Some(film) = film {
                tint *= film;
            }
            if self.thin {
                return out(-o, tint * (t / o.z), lobes.transmit, true, true);
            }
            let i = refract(o, self.eta)?;
            return out(i, tint * (t / -i.z), lobes.transmit, true, false);
        }
        // Between the rough reflection and transmission lobes: their probabilities together, then
        // the microfacet's own share (the pick's leftover of u_lobe, uniform within the pair).
        let (pick_reflect, pick_transmit, h) =
            if (pick_reflect || pick_transmit) && self.splits_at_microfacet() {
                let h = ggx.sample_vndf(o, u);
                let within = if pick_reflect {
                    u_lobe
                } else {
                    u_lobe - lobes.diffuse
                } / (lobes.reflect + lobes.transmit);
                let oh = o.dot(h);
                let through = self.dielectric_through(oh).0;
                let reflect = within < self.reflect_share(self.fresnel(oh), through);
                (reflect, !reflect, Some(h))
            } else {
                (pick_reflect, pick_transmit, None)
            };
        let i = if pick_reflect {
            let h = h.unwrap_or_else(|| ggx.sample_vndf(o, u));
            2.0 * o.dot(h) * h - o
        } else if pick_transmit {
            let h = h.unwrap_or_else(|| ggx.sample_vndf(o, u));
            if self.thin {
                let r = 2.0 * o.dot(h) * h - o;
                Vec3::new(r.x, r.y, -r.z)
            } else {
                // Refract about the microfacet normal; total internal reflection there gives no
                // transmitted direction (its energy is the reflection lobe's).
                let oh = o.dot(h);
                let sin2_t = (1.0 - oh * oh).max(0.0) / (self.eta * self.eta);
                if sin2_t >= 1.0 {
                    return None;
                }
                let cos_t = (1.0 - sin2_t).sqrt();
                -o / self.eta + (oh / self.eta - cos_t) * h
            }
        } else if let Some(dt) = &self.diffuse_transmission {
            // What is left of u_lobe within the diffuse lobe picks its side.
            let u_side = (u_lobe - lobes.reflect) / lobes.diffuse;
            dt.sample(dt.through_probability(self.base), u_side, u)
        } else {
            cosine_hemisphere(u)
        };
        if i.z == 0.0 || (pick_reflect && i.z < 0.0) || (pick_transmit && i.z > 0.0) {
            return None;
        }
        let (f, pdf) = self.lobe_mix_eval(o, i);
        out(i, f, pdf, false, false)
    }

    /// What a shadow ray keeps when it passes straight through this surface from `wo`'s side: the
    /// transmission of a thin smooth surface (its delta lobe points straight on), zero for any other.
    pub(super) fn base_straight_transmittance(&self, wo: Vec3) -> Vec3 {
        if !(self.thin && self.alpha == 0.0 && self.transmits()) {
            return Vec3::ZERO;
        }
        let cos = self.frame.n.dot(wo).abs();
        let (t, film) = self.dielectric_through(cos);
        let through = self.base * ((1.0 - self.metallic) * self.transmission * t);
        match film {
            Some(film) => through * film,
            None => through,
        }
    }
}

/// The direction refracted from local `o` (above) through the macro surface, or None under total
/// internal reflection.
fn refract(o: Vec3, eta: f32) -> Option<Vec3> {
    let sin2_t = (1.0 - o.z * o.z).max(0.0) / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some(Vec3::new(-o.x / eta, -o.y / eta, -cos_t))
}
