//! The three orthographic views of a diagram, as the lecture figures draw a scene: from above,
//! from the side, from the front. A view keeps two world axes and drops the third; `auto`
//! drops the axis along which the rays spread least, so that the plane drawn is the one that
//! best contains them (the pixel-intensity exercise lies in z = 0: auto draws it from the
//! front).

use std::fmt;
use std::str::FromStr;

use glam::{DVec2, DVec3};

/// An orthographic view: which world axes run across and up the drawing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// From above (+y): x across, z up the drawing (away from a camera that looks along +z).
    Top,
    /// From the side (+x): z across, y up.
    Side,
    /// From the front (−z): x across, y up, as a camera looking along +z sees the scene.
    Front,
}

/// The view asked for: one of the three, or the one that best holds the rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ViewChoice {
    /// From above.
    Top,
    /// From the side.
    Side,
    /// From the front.
    Front,
    /// Whichever view drops the axis along which the rays spread least.
    #[default]
    Auto,
}

impl View {
    /// The world point's place in the drawing.
    pub fn project(self, p: DVec3) -> DVec2 {
        match self {
            View::Top => DVec2::new(p.x, p.z),
            View::Side => DVec2::new(p.z, p.y),
            View::Front => DVec2::new(p.x, p.y),
        }
    }

    /// The world axis the view looks along (0 = x, 1 = y, 2 = z).
    pub fn dropped_axis(self) -> usize {
        match self {
            View::Top => 1,
            View::Side => 0,
            View::Front => 2,
        }
    }

    /// The world axes across and up the drawing.
    pub fn axes(self) -> (&'static str, &'static str) {
        match self {
            View::Top => ("x", "z"),
            View::Side => ("z", "y"),
            View::Front => ("x", "y"),
        }
    }

    /// The view's name (`top`, `side`, `front`).
    pub fn name(self) -> &'static str {
        match self {
            View::Top => "top",
            View::Side => "side",
            View::Front => "front",
        }
    }

    /// A short description for titles: "top view (x →, z ↑)".
    pub fn caption(self) -> String {
        let (h, v) = self.axes();
        format!("{} view ({h} →, {v} ↑)", self.name())
    }

    /// The view that drops the axis along which `points` spread least (by their standard
    /// deviation); ties go to front, then side, then top.
    pub fn best_for(points: &[DVec3]) -> View {
        if points.is_empty() {
            return View::Front;
        }
        let n = points.len() as f64;
        let mean = points.iter().copied().sum::<DVec3>() / n;
        let var = points
            .iter()
            .map(|p| (*p - mean) * (*p - mean))
            .sum::<DVec3>()
            / n;
        let spread = |v: View| var[v.dropped_axis()].sqrt();
        let scale = var.max_element().sqrt().max(f64::MIN_POSITIVE);
        let mut best = View::Front;
        for v in [View::Side, View::Top] {
            // Spreads within a millionth of the largest are equal: rounding, not geometry.
            if spread(v) < spread(best) - 1e-6 * scale {
                best = v;
            }
        }
        best
    }
}

impl ViewChoice {
    /// top → side → front → auto → top (the explorer's `v`).
    pub fn next(self) -> ViewChoice {
        match self {
            ViewChoice::Top => ViewChoice::Side,
            ViewChoice::Side => ViewChoice::Front,
            ViewChoice::Front => ViewChoice::Auto,
            ViewChoice::Auto => ViewChoice::Top,
        }
    }

    /// The view to draw the rays through `points` with.
    pub fn resolve(self, points: &[DVec3]) -> View {
        match self {
            ViewChoice::Top => View::Top,
            ViewChoice::Side => View::Side,
            ViewChoice::Front => View::Front,
            ViewChoice::Auto => View::best_for(points),
        }
    }

    /// The choice's name (`top`, `side`, `front`, `auto`).
    pub fn name(self) -> &'static str {
        match self {
            ViewChoice::Top => "top",
            ViewChoice::Side => "side",
            ViewChoice::Front => "front",
            ViewChoice::Auto => "auto",
        }
    }
}

impl fmt::Display for ViewChoice {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ViewChoice {
    type Err = String;

    fn from_str(s: &str) -> Result<ViewChoice, String> {
        match s {
            "top" => Ok(ViewChoice::Top),
            "side" => Ok(ViewChoice::Side),
            "front" => Ok(ViewChoice::Front),
            "auto" => Ok(ViewChoice::Auto),
            _ => Err(format!(
                "expected a view top, side, front or auto, got `{s}`"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_drops_the_axis_the_rays_do_not_leave() {
        // Rays in the plane z = 0 (lesson 08): seen from the front.
        let flat_z = [
            DVec3::new(-2.0, 3.5, 0.0),
            DVec3::ZERO,
            DVec3::new(1.0, 1.7, 0.0),
        ];
        assert_eq!(View::best_for(&flat_z), View::Front);
        // Rays along the z axis with a shadow ray up in y (lesson 07): x never changes.
        let along_z = [
            DVec3::new(0.0, 0.0, -5.0),
            DVec3::ZERO,
            DVec3::new(0.0, 5.0, -5.0),
        ];
        assert_eq!(View::best_for(&along_z), View::Side);
        // Rays in a floor plane y = 1: from above.
        let flat_y = [
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(3.0, 1.0, 2.0),
            DVec3::new(-1.0, 1.0, 5.0),
        ];
        assert_eq!(View::best_for(&flat_y), View::Top);
    }

    #[test]
    fn each_view_keeps_two_axes() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(View::Top.project(p), DVec2::new(1.0, 3.0));
        assert_eq!(View::Side.project(p), DVec2::new(3.0, 2.0));
        assert_eq!(View::Front.project(p), DVec2::new(1.0, 2.0));
        let mut v = ViewChoice::Top;
        for _ in 0..4 {
            v = v.next();
        }
        assert_eq!(v, ViewChoice::Top);
        assert_eq!("side".parse::<ViewChoice>(), Ok(ViewChoice::Side));
        assert!("diagonal".parse::<ViewChoice>().is_err());
    }
}
