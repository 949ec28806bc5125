//! The shading-model choices beside the glTF specification's own (the defaults): how the diffuse
//! base sits under the dielectric specular layer, and whether rough GGX lobes get back the energy
//! single scattering loses. A scene file's `[render]` table and the command line choose them.

/// How the dielectric specular layer weights the diffuse base under it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Layering {
    /// glTF appendix B's fresnel_mix: the diffuse gets 1 - F(V.H), per microfacet. Not energy
    /// conserving: a white dielectric reflects more than 1 at grazing views.
    #[default]
    Spec,
    /// Albedo scaling, as Blender's Principled BSDF layers it: the diffuse gets 1 - E(N.V), the
    /// specular layer's albedo estimated as Cycles does, by its Fresnel over the rough lobe's
    /// visible normals at the view.
    Albedo,
}

/// Scattering of the GGX specular lobes (metal and dielectric reflection).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum GgxScattering {
    /// glTF's single-scatter GGX: rough lobes lose the light that would scatter between
    /// microfacets (a white rough metal is darker than 1 in a white furnace).
    #[default]
    Single,
    /// Single scatter scaled by the energy it misses (Turquin 2019, as Cycles' multiscatter GGX):
    /// a white rough metal reflects 1.
    Multi,
}

/// Both choices; `Default` is the glTF specification's model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadingModel {
    pub layering: Layering,
    pub ggx: GgxScattering,
}
