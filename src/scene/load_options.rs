//! What to take from a file that holds several alternatives: which of a glTF file's scenes, which
//! of its animations. The default is what a viewer shows: the default scene and the first animation.

use std::fmt;

/// Which scene of a glTF file to load.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum SceneChoice {
    /// The file's `scene`, else its first, else every node that is nobody's child.
    #[default]
    Default,
    Index(usize),
    Name(String),
}

impl std::str::FromStr for SceneChoice {
    type Err = std::convert::Infallible;

    /// A number is an index, anything else a name.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(match s.parse::<usize>() {
            Ok(i) => SceneChoice::Index(i),
            Err(_) => SceneChoice::Name(s.to_owned()),
        })
    }
}

impl fmt::Display for SceneChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneChoice::Default => write!(f, "the default scene"),
            SceneChoice::Index(i) => write!(f, "scene {i}"),
            SceneChoice::Name(n) => write!(f, "scene '{n}'"),
        }
    }
}

/// The choices a loader makes among a file's alternatives.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    pub scene: SceneChoice,
    /// Index of the animation to keep (0: the first; an error when the file has animations but
    /// not this one).
    pub animation: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_indices_and_the_rest_names() {
        assert_eq!("2".parse::<SceneChoice>().unwrap(), SceneChoice::Index(2));
        assert_eq!(
            "Main".parse::<SceneChoice>().unwrap(),
            SceneChoice::Name("Main".into())
        );
        assert_eq!(
            "-1".parse::<SceneChoice>().unwrap(),
            SceneChoice::Name("-1".into())
        );
    }
}
