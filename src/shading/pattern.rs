//! Patterns: a colour O (or a coefficient kd, ks, kr, kt) that changes from point to point of a
//! surface. A pattern is a function of the point p in its own space: the hit point in the
//! object's own space (the coordinates its shape keys are written in), taken through the
//! inverse of the pattern's `transform`. At that p, with A and B its two values:
//!
//! ```text
//! stripes     A where ⌊x⌋ is even, else B
//! gradient    A + (B − A)·(x − ⌊x⌋)
//! rings       A where ⌊√(x² + z²)⌋ is even, else B
//! checker     A where ⌊x⌋ + ⌊y⌋ + ⌊z⌋ is even, else B   (solid cubes of side 1)
//! uv_checker  A where ⌊u·width⌋ + ⌊v·height⌋ is even, else B   ((u, v) from a mapping)
//! blend       (1 − w)·A + w·B
//! image       the image's colour at (u, v), bilinearly filtered (see `texture`)
//! ```
//!
//! A and B may be patterns themselves (nested), looked up at the same point in the outer
//! pattern's space.
//!
//! **Cell boundaries.** A floor at y = 0 is the boundary between the cells ⌊y⌋ = −1 and
//! ⌊y⌋ = 0, and the y of a computed hit point on it is off by rounding either way: a plain
//! ⌊y⌋ would flip between neighbouring cells from pixel to pixel ("pattern acne"). Every floor
//! here is taken of the coordinate plus `BOUNDARY` (10⁻⁹ of a cell): a cell runs from its lower
//! boundary (included) to its upper one (excluded), and a point less than 10⁻⁹ below a boundary
//! counts as on it. Rounding errors of hit points are some 10⁶ times smaller; no picture can show
//! a strip 10⁻⁹ of a cell wide.

use std::sync::Arc;

use glam::{DAffine3, DVec2, DVec3};

use super::texture::{Image, Mapping};
use crate::geometry::floor::floor;
use crate::geometry::uv::Edges;

/// A point less than this (in the pattern's units: cells of side 1) below a cell boundary
/// counts as on the boundary.
pub const BOUNDARY: f64 = 1e-9;

/// The cell a coordinate falls in: ⌊x⌋, with the boundary rule above.
#[inline]
pub fn cell(x: f64) -> f64 {
    floor(x + BOUNDARY)
}

/// Whether a whole number n is even: its last binary digit is 0. Below 2⁵³ in size a whole
/// f64 is exact in an i64; from 2⁵³ on its last binary digit is beyond the 53 it keeps, so every
/// finite one is even; NaN and the infinities are not.
fn even(n: f64) -> bool {
    if n.abs() < 9_007_199_254_740_992.0 {
        n as i64 & 1 == 0
    } else {
        n.is_finite()
    }
}

/// Where a pattern is looked up: the hit point in the object's own space, and the surface's own
/// (u, v) there (read by `mapping: uv`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatternPoint {
    /// The hit point in the space the pattern is looked up in (the object's own at the top).
    pub point: DVec3,
    /// The surface's own (u, v) at the hit point.
    pub uv: DVec2,
    /// Which of those end at an image's edges (`Shape::uv_edges`).
    pub edges: Edges,
}

impl PatternPoint {
    /// A point without texture coordinates (a pattern of space needs none).
    pub fn at(point: DVec3) -> PatternPoint {
        PatternPoint {
            point,
            uv: DVec2::ZERO,
            edges: Edges::NONE,
        }
    }
}

/// A value over a surface: a constant, or a pattern placed by its transform.
#[derive(Clone, Debug, PartialEq)]
pub enum Pattern {
    /// The same value everywhere.
    Constant(DVec3),
    /// A pattern with its placement.
    Placed(Box<Placed>),
}

/// A pattern with its placement.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    /// Which pattern, with its values A and B.
    pub kind: Kind,
    /// The inverse of the pattern's `transform`: from the space it is looked up in (the
    /// object's, or the outer pattern's) to its own. None for no transform.
    pub to_pattern: Option<DAffine3>,
}

/// The patterns of the scene file (formulas in the module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// A where ⌊x⌋ is even, else B.
    Stripes([Pattern; 2]),
    /// A + (B − A)·(x − ⌊x⌋).
    Gradient([Pattern; 2]),
    /// A where ⌊√(x² + z²)⌋ is even, else B.
    Rings([Pattern; 2]),
    /// A where ⌊x⌋ + ⌊y⌋ + ⌊z⌋ is even, else B.
    Checker([Pattern; 2]),
    /// (1 − w)·A + w·B.
    Blend {
        /// The weight w of B.
        weight: f64,
        /// A and B.
        values: [Pattern; 2],
    },
    /// A where ⌊u·width⌋ + ⌊v·height⌋ is even, else B.
    UvChecker {
        /// Checks across u.
        width: f64,
        /// Checks across v.
        height: f64,
        /// How the point gets its (u, v).
        mapping: Mapping,
        /// A and B.
        values: [Pattern; 2],
    },
    /// An image looked up at (u, v), bilinearly filtered.
    Image {
        /// The decoded image.
        image: Arc<Image>,
        /// How the point gets its (u, v).
        mapping: Mapping,
    },
}

impl Pattern {
    /// The value at a point.
    #[inline]
    pub fn value(&self, at: &PatternPoint) -> DVec3 {
        match self {
            Pattern::Constant(c) => *c,
            Pattern::Placed(p) => p.value(at),
        }
    }

    /// Whether it (or a pattern nested in it) reads the surface's own (u, v).
    pub fn needs_uv(&self) -> bool {
        let Pattern::Placed(p) = self else {
            return false;
        };
        match &p.kind {
            Kind::Image { mapping, .. } => *mapping == Mapping::Uv,
            Kind::UvChecker {
                mapping, values, ..
            } => *mapping == Mapping::Uv || values.iter().any(Pattern::needs_uv),
            Kind::Stripes(v) | Kind::Gradient(v) | Kind::Rings(v) | Kind::Checker(v) => {
                v.iter().any(Pattern::needs_uv)
            }
            Kind::Blend { values, .. } => values.iter().any(Pattern::needs_uv),
        }
    }

    /// The largest value it can take, per channel: what it is worth to know whether a surface
    /// can reflect or transmit at all.
    pub fn max(&self) -> DVec3 {
        let Pattern::Placed(p) = self else {
            return self.value(&PatternPoint::at(DVec3::ZERO));
        };
        match &p.kind {
            Kind::Stripes([a, b])
            | Kind::Gradient([a, b])
            | Kind::Rings([a, b])
            | Kind::Checker([a, b])
            | Kind::Blend { values: [a, b], .. }
            | Kind::UvChecker { values: [a, b], .. } => a.max().max(b.max()),
            Kind::Image { image, .. } => image.max(),
        }
    }

    /// What it is, in a few words ("checker", "image wood.png, spherical mapping").
    pub fn describe(&self) -> String {
        match self {
            Pattern::Constant(_) => "constant".into(),
            Pattern::Placed(p) => match &p.kind {
                Kind::Stripes(_) => "stripes".into(),
                Kind::Gradient(_) => "gradient".into(),
                Kind::Rings(_) => "rings".into(),
                Kind::Checker(_) => "checker".into(),
                Kind::Blend { .. } => "blend".into(),
                Kind::UvChecker {
                    width,
                    height,
                    mapping,
                    ..
                } => format!("uv_checker {width}×{height}, {} mapping", mapping.name()),
                Kind::Image { image, mapping } => {
                    format!("image {}, {} mapping", image.name, mapping.name())
                }
            },
        }
    }

    /// The point in this pattern's own space (what its formula is evaluated at), and the (u, v)
    /// of its mapping when it is a texture or a uv checker, with the coordinates of those that
    /// end at an image's edges: what a ray tree shows.
    pub fn lookup(&self, at: &PatternPoint) -> (DVec3, Option<(DVec2, Edges)>) {
        match self {
            Pattern::Constant(_) => (at.point, None),
            Pattern::Placed(p) => {
                let at = p.place(at);
                let uv = match &p.kind {
                    Kind::Image { mapping, .. } | Kind::UvChecker { mapping, .. } => {
                        Some((mapping.uv(&at), mapping.edges(&at)))
                    }
                    _ => None,
                };
                (at.point, uv)
            }
        }
    }
}

impl Placed {
    /// The point in the pattern's own space: through the inverse of its transform (the surface's
    /// (u, v) too, as the point (u, v, 0), for `mapping: uv`).
    fn place(&self, at: &PatternPoint) -> PatternPoint {
        match &self.to_pattern {
            None => *at,
            Some(m) => PatternPoint {
                point: m.transform_point3(at.point),
                uv: m.transform_point3(at.uv.extend(0.0)).truncate(),
                edges: at.edges,
            },
        }
    }

    /// The value at a point: looked up where the point is in the pattern's own space.
    fn value(&self, at: &PatternPoint) -> DVec3 {
        // Without a transform the point is looked up where it is: a copy of it, read back
        // whole just after it was written field by field, would wait on those stores.
        match &self.to_pattern {
            None => self.kind.value(at),
            Some(_) => self.kind.value(&self.place(at)),
        }
    }
}

impl Kind {
    /// The value at a point in the pattern's own space.
    fn value(&self, at: &PatternPoint) -> DVec3 {
        let p = at.point;
        let pick = |[a, b]: &[Pattern; 2], first: bool| {
            if first {
                a.value(at)
            } else {
                b.value(at)
            }
        };
        match self {
            Kind::Stripes(v) => pick(v, even(cell(p.x))),
            Kind::Rings(v) => pick(v, even(cell((p.x * p.x + p.z * p.z).sqrt()))),
            Kind::Checker(v) => pick(v, even(cell(p.x) + cell(p.y) + cell(p.z))),
            Kind::Gradient([a, b]) => {
                // The fraction of the way across the cell, never below 0 at its boundary.
                let f = (p.x - cell(p.x)).max(0.0);
                let a = a.value(at);
                a + (b.value(at) - a) * f
            }
            Kind::Blend {
                weight,
                values: [a, b],
            } => a.value(at).lerp(b.value(at), *weight),
            Kind::UvChecker {
                width,
                height,
                mapping,
                values,
            } => {
                let uv = mapping.uv(at);
                pick(values, even(cell(uv.x * width) + cell(uv.y * height)))
            }
            Kind::Image { image, mapping } => image.bilinear(mapping.uv(at), mapping.edges(at)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const WHITE: DVec3 = DVec3::ONE;
    const BLACK: DVec3 = DVec3::ZERO;

    fn two(kind: fn([Pattern; 2]) -> Kind, to_pattern: Option<DAffine3>) -> Pattern {
        Pattern::Placed(Box::new(Placed {
            kind: kind([Pattern::Constant(WHITE), Pattern::Constant(BLACK)]),
            to_pattern,
        }))
    }

    fn at(x: f64, y: f64, z: f64) -> PatternPoint {
        PatternPoint::at(DVec3::new(x, y, z))
    }

    /// The Ray Tracer Challenge, chapter "Patterns": a stripe pattern is constant in y and z
    /// and alternates in x.
    #[test]
    fn stripes_of_the_book() {
        let s = two(Kind::Stripes, None);
        for (p, c) in [
            ((0.0, 0.0, 0.0), WHITE),
            ((0.0, 1.0, 0.0), WHITE),
            ((0.0, 2.0, 0.0), WHITE),
            ((0.0, 0.0, 1.0), WHITE),
            ((0.0, 0.0, 2.0), WHITE),
            ((0.9, 0.0, 0.0), WHITE),
            ((1.0, 0.0, 0.0), BLACK),
            ((-0.1, 0.0, 0.0), BLACK),
            ((-1.0, 0.0, 0.0), BLACK),
            ((-1.1, 0.0, 0.0), WHITE),
        ] {
            assert_eq!(s.value(&at(p.0, p.1, p.2)), c, "{p:?}");
        }
    }

    /// "A gradient linearly interpolates between colors".
    #[test]
    fn gradient_of_the_book() {
        let g = two(Kind::Gradient, None);
        for (x, c) in [(0.0, 1.0), (0.25, 0.75), (0.5, 0.5), (0.75, 0.25)] {
            assert_eq!(g.value(&at(x, 0.0, 0.0)), DVec3::splat(c), "x = {x}");
        }
    }

    /// "A ring should extend in both x and z".
    #[test]
    fn rings_of_the_book() {
        let r = two(Kind::Rings, None);
        assert_eq!(r.value(&at(0.0, 0.0, 0.0)), WHITE);
        assert_eq!(r.value(&at(1.0, 0.0, 0.0)), BLACK);
        assert_eq!(r.value(&at(0.0, 0.0, 1.0)), BLACK);
        assert_eq!(r.value(&at(0.708, 0.0, 0.708)), BLACK);
    }

    /// "Checkers should repeat in x, y and z".
    #[test]
    fn checker_of_the_book() {
        let c = two(Kind::Checker, None);
        for (p, want) in [
            ((0.0, 0.0, 0.0), WHITE),
            ((0.99, 0.0, 0.0), WHITE),
            ((1.01, 0.0, 0.0), BLACK),
            ((0.0, 0.99, 0.0), WHITE),
            ((0.0, 1.01, 0.0), BLACK),
            ((0.0, 0.0, 0.99), WHITE),
            ((0.0, 0.0, 1.01), BLACK),
        ] {
            assert_eq!(c.value(&at(p.0, p.1, p.2)), want, "{p:?}");
        }
    }

    /// Parity by its definition: n is even when n = 2k for a whole k, negative n, the odd
    /// numbers just below 2⁵³ and whole numbers past it included; NaN and the infinities are
    /// not even.
    #[test]
    fn even_and_odd_cells() {
        for k in [
            -1e6,
            -3.0,
            -1.0,
            0.0,
            1.0,
            2.0,
            2f64.powi(52) - 1.0,
            -(2f64.powi(52) - 1.0),
            2f64.powi(52),
            2f64.powi(60),
        ] {
            assert!(even(2.0 * k), "{}", 2.0 * k);
            if k.abs() < 2f64.powi(52) {
                assert!(!even(2.0 * k + 1.0), "{}", 2.0 * k + 1.0);
            }
        }
        assert!(even(-0.0));
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(!even(x), "{x}");
        }
    }

    /// "Stripes with a pattern transformation": scaling(2, 2, 2), at (1.5, 0, 0) → white.
    #[test]
    fn a_transformed_pattern_is_looked_up_through_its_inverse() {
        let scale = DAffine3::from_scale(DVec3::splat(2.0)).inverse();
        let s = two(Kind::Stripes, Some(scale));
        assert_eq!(s.value(&at(1.5, 0.0, 0.0)), WHITE);
        assert_eq!(s.value(&at(2.5, 0.0, 0.0)), BLACK);
    }

    /// A floor at y = 0 and y = −1: hit points a rounding error either side of the boundary
    /// fall in one cell, the upper one.
    #[test]
    fn points_a_rounding_error_off_a_boundary_fall_in_one_cell() {
        let c = two(Kind::Checker, None);
        for y in [0.0, -0.0, 1e-16, -1e-16, -4e-15] {
            assert_eq!(c.value(&at(0.5, y, 0.5)), WHITE, "y = {y:e}");
        }
        for y in [-1.0, -1.0 + 1e-16, -1.0 - 2e-16] {
            assert_eq!(c.value(&at(0.5, y, 0.5)), BLACK, "y = {y:e}");
        }
        // Well below a boundary, the cell below.
        assert_eq!(c.value(&at(0.5, -1e-6, 0.5)), BLACK);
        // The gradient starts its cell at 0, never below.
        let g = two(Kind::Gradient, None);
        assert_eq!(g.value(&at(-1e-12, 0.0, 0.0)), WHITE);
    }

    /// A nested pattern is looked up in the outer pattern's space, then through its own
    /// transform: stripes of checkers.
    #[test]
    fn nested_patterns_take_their_values_at_the_same_point() {
        let checker = two(Kind::Checker, Some(DAffine3::from_scale(DVec3::splat(0.5))));
        let nested = Pattern::Placed(Box::new(Placed {
            kind: Kind::Stripes([checker, Pattern::Constant(DVec3::new(1.0, 0.0, 0.0))]),
            to_pattern: None,
        }));
        // x in [0, 1): the checker, whose inverse transform halves the point (cells of side 2).
        assert_eq!(nested.value(&at(0.5, 0.5, 0.5)), WHITE);
        assert_eq!(nested.value(&at(0.5, 2.5, 0.5)), BLACK);
        assert_eq!(nested.value(&at(1.5, 0.5, 0.5)), DVec3::new(1.0, 0.0, 0.0));
    }

    /// "Checker pattern in 2D": uv_checkers(2, 2, black, white).
    #[test]
    fn uv_checker_of_the_book() {
        let c = Pattern::Placed(Box::new(Placed {
            kind: Kind::UvChecker {
                width: 2.0,
                height: 2.0,
                mapping: Mapping::Uv,
                values: [Pattern::Constant(BLACK), Pattern::Constant(WHITE)],
            },
            to_pattern: None,
        }));
        let uv = |u, v| PatternPoint {
            point: DVec3::ZERO,
            uv: DVec2::new(u, v),
            edges: Edges::NONE,
        };
        assert_eq!(c.value(&uv(0.0, 0.0)), BLACK);
        assert_eq!(c.value(&uv(0.5, 0.0)), WHITE);
        assert_eq!(c.value(&uv(0.0, 0.5)), WHITE);
        assert_eq!(c.value(&uv(0.5, 0.5)), BLACK);
        assert_eq!(c.value(&uv(1.0, 1.0)), BLACK);
    }
}
