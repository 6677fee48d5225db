//! A material's patterns and textures: each `{ pattern: ... }` or `{ image: ... }` checked and
//! compiled into a `Pattern` (its transform inverted, its values compiled in turn, its image
//! read and decoded once per scene).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DAffine3, DVec3};
use serde_saphyr::Spanned;

use super::objects::transform;
use super::{invalid, number, pos, Invalid, Pos};
use crate::scene::format::{PatternName, PatternSpec, Varying};
use crate::shading::pattern::{Kind, Placed};
use crate::shading::texture::{Image, Mapping};
use crate::shading::Pattern;

/// Compiles patterns, reading the images they name relative to the scene's folder.
pub struct Textures<'a> {
    base: &'a Path,
    loaded: HashMap<PathBuf, Arc<Image>>,
    /// The images' files, in the order first named.
    files: Vec<PathBuf>,
}

/// What a pattern's values are: colours, or one coefficient (grey values).
#[derive(Clone, Copy)]
pub struct Of<'a> {
    pub material: &'a str,
    pub key: &'a str,
    pub scalar: bool,
}

impl Of<'_> {
    fn say(&self, what: impl std::fmt::Display) -> String {
        format!("material `{}`: {}: {what}", self.material, self.key)
    }
}

impl<'a> Textures<'a> {
    pub fn new(base: &'a Path) -> Textures<'a> {
        Textures {
            base,
            loaded: HashMap::new(),
            files: Vec::new(),
        }
    }

    /// The image files read, each once, in the order first named.
    pub fn into_files(self) -> Vec<PathBuf> {
        self.files
    }

    /// A value: a constant, or a pattern.
    pub fn varying(&mut self, v: &Spanned<Varying>, of: Of) -> Result<Pattern, Invalid> {
        match &v.value {
            Varying::Value(t) => constant(t.0, pos(v), of).map(Pattern::Constant),
            Varying::Pattern(spec) => self.pattern(spec, pos(v), of),
        }
    }

    fn pattern(&mut self, spec: &PatternSpec, p: Pos, of: Of) -> Result<Pattern, Invalid> {
        let kind = match (&spec.pattern, &spec.image) {
            (Some(_), Some(i)) => {
                return invalid(pos(i), of.say("give `pattern` or `image`, not both"))
            }
            (None, None) => {
                return invalid(
                    p,
                    of.say("a pattern needs `pattern: stripes | gradient | rings | checker | uv_checker | blend`, or `image: FILE` for a texture"),
                )
            }
            (None, Some(file)) => {
                if let Some(c) = &spec.colors {
                    return invalid(pos(c), of.say("an image texture takes no `colors`"));
                }
                Kind::Image {
                    image: self.image(file, of)?,
                    mapping: mapping(spec),
                }
            }
            (Some(name), None) => self.kind(spec, name, p, of)?,
        };
        for (key, value) in [("width", &spec.width), ("height", &spec.height)] {
            if let Some(v) = value {
                if !matches!(kind, Kind::UvChecker { .. }) {
                    return invalid(pos(v), of.say(format!("`{key}` belongs to a uv_checker")));
                }
            }
        }
        if let Some(m) = &spec.mapping {
            if !matches!(kind, Kind::UvChecker { .. } | Kind::Image { .. }) {
                return invalid(
                    pos(m),
                    of.say("`mapping` belongs to an image texture or a uv_checker"),
                );
            }
        }
        if let Some(w) = &spec.weight {
            if !matches!(kind, Kind::Blend { .. }) {
                return invalid(pos(w), of.say("`weight` belongs to a blend"));
            }
        }
        let placed = transform(&spec.transform)?;
        Ok(Pattern::Placed(Box::new(Placed {
            kind,
            to_pattern: (placed.to_world != DAffine3::IDENTITY).then_some(placed.to_local),
        })))
    }

    fn kind(
        &mut self,
        spec: &PatternSpec,
        name: &Spanned<PatternName>,
        p: Pos,
        of: Of,
    ) -> Result<Kind, Invalid> {
        let Some(colors) = &spec.colors else {
            return invalid(
                pos(name),
                of.say("a pattern needs its two values: `colors: [A, B]`"),
            );
        };
        if colors.value.len() != 2 {
            return invalid(
                pos(colors),
                of.say(format!(
                    "a pattern takes two values A and B, got {}",
                    colors.value.len()
                )),
            );
        }
        let values = [
            self.varying(&colors.value[0], of)?,
            self.varying(&colors.value[1], of)?,
        ];
        let positive = |v: &Option<Spanned<crate::scene::format::Num>>, key: &str| match v {
            None => invalid(p, of.say(format!("a uv_checker needs `{key}` (squares)"))),
            Some(v) if v.value.0 > 0.0 => Ok(v.value.0),
            Some(v) => invalid(
                pos(v),
                of.say(format!("`{key}` must be > 0, got {}", v.value)),
            ),
        };
        Ok(match name.value {
            PatternName::Stripes => Kind::Stripes(values),
            PatternName::Gradient => Kind::Gradient(values),
            PatternName::Rings => Kind::Rings(values),
            PatternName::Checker => Kind::Checker(values),
            PatternName::UvChecker => Kind::UvChecker {
                width: positive(&spec.width, "width")?,
                height: positive(&spec.height, "height")?,
                mapping: mapping(spec),
                values,
            },
            PatternName::Blend => Kind::Blend {
                weight: match &spec.weight {
                    None => 0.5,
                    Some(w) if (0.0..=1.0).contains(&w.value.0) => w.value.0,
                    Some(w) => {
                        return invalid(
                            pos(w),
                            of.say(format!("a blend's weight lies in [0, 1], got {}", w.value)),
                        )
                    }
                },
                values,
            },
        })
    }

    /// The image a texture names, read once however many patterns name it.
    fn image(&mut self, file: &Spanned<String>, of: Of) -> Result<Arc<Image>, Invalid> {
        let path = self.base.join(&file.value);
        if let Some(image) = self.loaded.get(&path) {
            return Ok(image.clone());
        }
        let image = Image::load(&path, &file.value).or_else(|e| invalid(pos(file), of.say(e)))?;
        let image = Arc::new(image);
        self.files.push(path.clone());
        self.loaded.insert(path, image.clone());
        Ok(image)
    }
}

fn mapping(spec: &PatternSpec) -> Mapping {
    spec.mapping.as_ref().map_or(Mapping::Uv, |m| m.value)
}

/// A constant value: a colour (no channel below 0), or a coefficient (a number ≥ 0).
fn constant(v: DVec3, p: Pos, of: Of) -> Result<DVec3, Invalid> {
    let whose = format!("material `{}`: {}", of.material, of.key);
    if of.scalar && !(v.x == v.y && v.y == v.z) {
        return invalid(p, format!("{whose} must be a number, not a colour"));
    }
    if v.min_element() < 0.0 {
        return invalid(
            p,
            if of.scalar {
                format!("{whose} must be ≥ 0, got {}", number(v.x))
            } else {
                format!("{whose} must be ≥ 0")
            },
        );
    }
    Ok(v)
}
