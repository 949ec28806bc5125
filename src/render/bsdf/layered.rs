//! The layered material: clearcoat over sheen over the base, as KHR_materials_clearcoat's
//! fresnel_coat (the layers below get 1 - weight * Schlick(N_c . V)) and KHR_materials_sheen's albedo
//! scaling (the base gets min(1 - max(sheen) E(N.V), 1 - max(sheen) E(N.L))) define. One lobe is
//! sampled, chosen by its estimated share of the reflected light; eval returns the sum of all lobes
//! and the pdf the whole choice gives, so MIS sees the density the sampler really has.

use glam::{Vec2, Vec3};

use super::{choice_probabilities, Bsdf, BsdfSample};

/// Probabilities of sampling each layer.
#[derive(Clone, Copy, Debug)]
pub(super) struct LayerChoice {
    pub coat: f32,
    pub sheen: f32,
    pub base: f32,
}

impl Bsdf {
    /// The coat's Fresnel share at `wo` (0 without a coat).
    fn coat_share(&self, wo: Vec3) -> f32 {
        self.coat.map_or(0.0, |c| c.fresnel(wo))
    }

    /// What reaches the base through the layers above it, for incidence cosines `cos_o`, `cos_i`.
    pub(super) fn layer_scale(&self, wo: Vec3, cos_o: f32, cos_i: f32) -> f32 {
        let sheen = self.sheen.map_or(1.0, |s| {
            let m = s.color.max_element();
            1.0 - m * s.albedo(cos_o).max(s.albedo(cos_i))
        });
        (1.0 - self.coat_share(wo)) * sheen.max(0.0)
    }

    /// Layer choice at `wo` (local `o`): proportional to each layer's estimated reflectance, mixed
    /// with a tenth of a uniform choice so that none is starved.
    pub(super) fn layer_choice(&self, wo: Vec3, o: Vec3) -> LayerChoice {
        let fc = self.coat_share(wo);
        let es = self
            .sheen
            .map_or(0.0, |s| s.color.max_element() * s.albedo(o.z));
        let w = [
            if self.coat.is_some() { fc } else { 0.0 },
            if self.sheen.is_some() {
                (1.0 - fc) * es
            } else {
                0.0
            },
            (1.0 - fc) * (1.0 - es) * self.base_estimate(o.z).max(0.05),
        ];
        let [coat, sheen, base] = choice_probabilities(w);
        LayerChoice { coat, sheen, base }
    }

    /// Value of every non-delta lobe and the pdf of choosing and sampling `wi`, for world directions.
    pub(super) fn layered_eval(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (o, i) = (self.frame.to_local(wo), self.frame.to_local(wi));
        if o.z <= 0.0 || i.z == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let choice = self.layer_choice(wo, o);
        let (fb, pb) = self.base_eval(o, i);
        let mut f = fb * self.layer_scale(wo, o.z, i.z.abs());
        let mut pdf = choice.base * pb;
        if let Some(s) = &self.sheen {
            let (fs, ps) = s.eval(o, i);
            f += fs * (1.0 - self.coat_share(wo));
            pdf += choice.sheen * ps;
        }
        if let Some(c) = &self.coat {
            let (fc, pc) = c.eval(wo, wi);
            f += Vec3::splat(fc);
            pdf += choice.coat * pc;
        }
        (f, pdf)
    }

    /// Samples one layer's lobe; non-delta samples carry the whole material's value and pdf.
    pub(super) fn layered_sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let o = self.frame.to_local(wo);
        if o.z <= 0.0 {
            return None;
        }
        let choice = self.layer_choice(wo, o);
        let wi = if u_lobe < choice.coat {
            let coat = self.coat?;
            let wi = coat.sample(wo, u)?;
            if coat.is_delta() {
                let cos = wi.dot(self.frame.n);
                return (cos > 0.0).then(|| BsdfSample {
                    wi,
                    f: Vec3::splat(coat.fresnel(wo) / cos),
                    pdf: choice.coat,
                    delta: true,
                    straight: false,
                });
            }
            wi
        } else if u_lobe < choice.coat + choice.sheen {
            self.frame.to_world(self.sheen?.sample(o, u)?)
        } else {
            // The base's own lobe choice reuses what is left of u_lobe.
            let u_base = ((u_lobe - choice.coat - choice.sheen) / choice.base).min(1.0 - 1e-7);
            let mut s = self.base_sample(wo, u_base, u)?;
            if s.delta {
                let cos_i = self.frame.n.dot(s.wi).abs();
                s.f *= self.layer_scale(wo, o.z, cos_i);
                s.pdf *= choice.base;
                return (s.f != Vec3::ZERO).then_some(s);
            }
            s.wi
        };
        let (f, pdf) = self.layered_eval(wo, wi);
        (pdf > 0.0 && f != Vec3::ZERO).then_some(BsdfSample {
            wi,
            f,
            pdf,
            delta: false,
            straight: false,
        })
    }
}
