//! The `[render]` table of a scene file: render settings that command-line flags given explicitly
//! override, with enum values spelled as on the command line.

use serde::Deserialize;

use crate::film::filter::FilterKind;
use crate::sample::SamplerKind;
use crate::scene::shading::{GgxScattering, Layering};

/// Render settings a scene file may carry; command-line flags given explicitly win over them.
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FileSettings {
    pub width: Option<usize>,
    pub height: Option<usize>,
    pub spp: Option<u32>,
    pub max_depth: Option<u32>,
    pub seed: Option<u64>,
    #[serde(default, deserialize_with = "value_enum")]
    pub sampler: Option<SamplerKind>,
    #[serde(default, deserialize_with = "value_enum")]
    pub filter: Option<FilterKind>,
    pub backend: Option<String>,
    #[serde(default, deserialize_with = "value_enum")]
    pub layering: Option<Layering>,
    #[serde(default, deserialize_with = "value_enum")]
    pub ggx: Option<GgxScattering>,
}

/// A `clap::ValueEnum` read from its command-line name, so the file and the flags spell values alike.
fn value_enum<'de, D, T>(d: D) -> Result<Option<T>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: clap::ValueEnum,
{
    let s = String::deserialize(d)?;
    T::from_str(&s, true)
        .map(Some)
        .map_err(|_| serde::de::Error::custom(format!("unknown value '{s}'")))
}
