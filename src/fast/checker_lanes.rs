//! The checker's lookup at four surfaces of a packet at once, for the usual checkered surface:
//! a material whose only pattern is a checker of two constant colours, untransformed, on a leaf
//! without a transform (a checkered floor). The pattern point is then the hit point itself, and
//! each lane does what `Kind::value` does for it:
//!
//! ```text
//! n = ⌊x + ε⌋ + ⌊y + ε⌋ + ⌊z + ε⌋      (`cell`, summed in that order)
//! O = A where n is even, else B
//! ```
//!
//! A sum of whole numbers is whole, so n is even exactly where n/2 is whole (n/2 is exact, and
//! from 2⁵³ on every finite n is even, as `even` has it) and n is finite; NaN and ±∞ are odd.

use glam::DVec3;

use super::lanes::LANES;
use super::search::FastScene;
use super::simd::F64x4;
use crate::scene::Interaction;
use crate::shading::pattern::{Kind, Placed, BOUNDARY};
use crate::shading::{Material, Pattern};

/// A's and B's colours of a material that the lanes can paint: its one pattern a checker of
/// two constant colours, without a transform of its own.
pub(super) fn checker_colors(material: &Material) -> Option<[DVec3; 2]> {
    let patterns = material.patterns.as_ref()?;
    let coefficients = [&patterns.kd, &patterns.ks, &patterns.kr, &patterns.kt];
    if coefficients.iter().any(|p| p.is_some()) {
        return None;
    }
    let Some(Pattern::Placed(placed)) = &patterns.color else {
        return None;
    };
    let Placed {
        kind: Kind::Checker([Pattern::Constant(a), Pattern::Constant(b)]),
        to_pattern: None,
    } = placed.as_ref()
    else {
        return None;
    };
    Some([*a, *b])
}

/// Whether the lanes paint the surface `si` of material `m`.
#[inline(always)]
pub(super) fn in_lanes(fast: &FastScene, m: &Material, si: &Interaction) -> bool {
    // Most materials have no patterns: they are answered without a look in the table.
    m.patterns.is_some()
        && fast.checker(si.material).is_some()
        && fast.scene.leaves[si.leaf as usize].transform.is_none()
}

/// Paints the surfaces of a packet in the lanes `taken` (bit i: `shaded[i]`, one that
/// `in_lanes` took), four at a time.
#[inline(always)]
pub(super) fn paint_checkers<V: F64x4, const N: usize>(
    fast: &FastScene,
    shaded: &mut [Option<Interaction>; N],
    mut taken: u32,
) {
    while taken != 0 {
        // Up to four surfaces; a short group repeats its last.
        let mut lanes = [0; LANES];
        let mut count = 0;
        while taken != 0 && count < LANES {
            // `% N` spares the bounds checks: bit i is set only for i < N.
            lanes[count] = taken.trailing_zeros() as usize % N;
            taken &= taken - 1;
            count += 1;
        }
        for k in count..LANES {
            lanes[k] = lanes[count - 1];
        }
        let point = |k: usize| shaded[lanes[k]].as_ref().map_or(DVec3::ZERO, |si| si.point);
        let even = even_cells::<V>([point(0), point(1), point(2), point(3)]);
        for (k, &i) in lanes[..count].iter().enumerate() {
            let Some(si) = &mut shaded[i] else { continue };
            if let Some([a, b]) = fast.checker(si.material) {
                si.paint.color = if even >> k & 1 == 1 { *a } else { *b };
            }
        }
    }
}

/// Bit k set where the checker's cell of `points[k]` is even (its colour is A).
#[inline(always)]
fn even_cells<V: F64x4>([p0, p1, p2, p3]: [DVec3; LANES]) -> u32 {
    let axis = |a: f64, b: f64, c: f64, d: f64| V::new([a, b, c, d]);
    even_cells_of::<V>([
        axis(p0.x, p1.x, p2.x, p3.x),
        axis(p0.y, p1.y, p2.y, p3.y),
        axis(p0.z, p1.z, p2.z, p3.z),
    ])
}

/// Bit k set where the checker's cell of the point in lane k is even (its colour is A).
#[inline(always)]
pub(super) fn even_cells_of<V: F64x4>([x, y, z]: [V; 3]) -> u32 {
    let cell = |a: V| (a + V::splat(BOUNDARY)).floor();
    let n = cell(x) + cell(y) + cell(z);
    let half = n * V::splat(0.5);
    (half.floor().simd_eq(half) & n.is_finite()).to_bitmask()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::{with_lanes, Wide};
    use crate::shading::PatternPoint;

    /// The core's checker of A = (1, 1, 1) and B = (0, 0, 0) at p: whether it is A.
    fn core_says_even(p: DVec3) -> bool {
        let checker = Pattern::Placed(Box::new(Placed {
            kind: Kind::Checker([
                Pattern::Constant(DVec3::ONE),
                Pattern::Constant(DVec3::ZERO),
            ]),
            to_pattern: None,
        }));
        let at = PatternPoint::at(p);
        checker.value(&at) == DVec3::ONE
    }

    fn assert_lanes_agree<V: F64x4>(points: &[DVec3]) {
        for four in points.chunks_exact(4) {
            let even = even_cells::<V>([four[0], four[1], four[2], four[3]]);
            for (k, p) in four.iter().enumerate() {
                assert_eq!(even >> k & 1 == 1, core_says_even(*p), "at {p}");
            }
        }
    }

    /// Both kinds of lanes pick the core's colour at every point: cells either side of zero,
    /// points on, just below and within 10⁻⁹ below a cell boundary (which counts as on it),
    /// sums of cells that cancel, coordinates near and past 2⁵² and 2⁵³ (where every f64 is
    /// whole, and every sum from 2⁵³ on even), and NaN and ±∞ (odd, as the core has them).
    #[test]
    fn lanes_pick_the_cores_colour() {
        let big = 2f64.powi(52);
        let mut values = vec![
            0.0,
            -0.0,
            1e-300,
            -1e-300,
            -1e-10,
            -2e-9,
            0.5,
            -0.5,
            1.0,
            -1.0,
            1.0 - 1e-10,
            1.0 - 1e-8,
            3.0,
            -3.0,
            big - 1.0,
            big,
            big + 2.0,
            -big,
            2.0 * big,
            2.0 * big + 2.0,
            -2.0 * big - 2.0,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        values.extend((-40..=40).map(|i| i as f64 * 0.37));
        let mut points = vec![];
        for (i, &x) in values.iter().enumerate() {
            for (j, &y) in values.iter().enumerate().step_by(3) {
                let z = values[(i * 7 + j * 13) % values.len()];
                points.extend([DVec3::new(x, y, z), DVec3::new(z, x, y)]);
            }
        }
        points.truncate(points.len() / 4 * 4);
        assert_lanes_agree::<Wide>(&points);
        with_lanes!(V => assert_lanes_agree::<V>(&points));
        // Both colours are picked, somewhere.
        let evens = points.iter().filter(|p| core_says_even(**p)).count();
        assert!(
            evens > 100 && evens < points.len() - 100,
            "{evens} of {}",
            points.len()
        );
    }
}
