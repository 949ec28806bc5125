//! The sizes of scene glint refuses, whatever the file format: a small file can describe an
//! enormous scene (a mesh placed a billion times, a CSG tree ten thousand deep), and it is refused
//! with an error naming the file and the element before the memory (or the stack) runs out.

/// Most instances (placed meshes) in a scene: 16.7 million.
pub const MAX_INSTANCES: usize = 1 << 24;
/// Most triangles in the world, counting each instance's: 134 million (the accelerators hold each
/// static instance's triangles in world space, some 100 bytes apiece).
pub const MAX_WORLD_TRIANGLES: usize = 1 << 27;
/// Deepest CSG tree (operations inside operations); every ray walks it recursively.
pub const MAX_CSG_DEPTH: usize = 24;
/// Deepest nesting of arrays and inline tables in a scene file, checked on the text before it is
/// parsed: the parser recurses (the `toml` crate stops at 80 with a bare "max recursion depth"), as
/// does the reading of a CSG tree (two levels of text per level of tree).
pub const MAX_TOML_NESTING: usize = 64;

/// What makes a scene too large, or None.
pub fn too_large(instances: usize, world_triangles: usize) -> Option<String> {
    if instances > MAX_INSTANCES {
        Some(format!(
            "{instances} instances are more than the {MAX_INSTANCES} glint accepts"
        ))
    } else if world_triangles > MAX_WORLD_TRIANGLES {
        Some(format!(
            "{world_triangles} triangles (counting every instance) are more than the {MAX_WORLD_TRIANGLES} glint accepts"
        ))
    } else {
        None
    }
}

/// The line (from 1) where nesting of `[`/`{` in TOML text first exceeds `MAX_TOML_NESTING`, or
/// None. Strings and comments are skipped; table headers (`[a]`, `[[a]]`) nest at most twice.
pub fn toml_too_deep(text: &str) -> Option<usize> {
    let (mut depth, mut line) = (0usize, 1usize);
    let mut chars = text.chars().peekable();
    let mut quote: Option<char> = None;
    while let Some(c) = chars.next() {
        if c == '\n' {
            line += 1;
        }
        match (quote, c) {
            // An escape: the next character is part of the string (a newline still counts).
            (Some('"'), '\\') => line += usize::from(chars.next() == Some('\n')),
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '#') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        line += 1;
                        break;
                    }
                }
            }
            (None, '[' | '{') => {
                depth += 1;
                if depth > MAX_TOML_NESTING {
                    return Some(line);
                }
            }
            (None, ']' | '}') => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nesting_is_counted_outside_strings_and_comments() {
        let deep = format!("a = {}1{}\n", "[".repeat(300), "]".repeat(300));
        assert_eq!(toml_too_deep(&format!("x = 1\n{deep}")), Some(2));
        let quoted = format!(
            "a = \"{}\" # {}\nb = '{}'\n",
            "[".repeat(300),
            "{".repeat(300),
            "[".repeat(300)
        );
        assert_eq!(toml_too_deep(&quoted), None);
        let fine = format!("[[asset]]\na = {}1{}\n", "[".repeat(60), "]".repeat(60));
        assert_eq!(toml_too_deep(&fine), None);
    }

    #[test]
    fn instance_and_triangle_caps_name_the_count() {
        assert!(too_large(MAX_INSTANCES, MAX_WORLD_TRIANGLES).is_none());
        let e = too_large(MAX_INSTANCES + 1, 0).unwrap();
        assert!(e.contains(&(MAX_INSTANCES + 1).to_string()), "{e}");
        assert!(too_large(1, MAX_WORLD_TRIANGLES + 1)
            .unwrap()
            .contains("triangles"));
    }
}
