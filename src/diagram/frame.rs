//! The part of a view's plane a diagram shows: a rectangle in world units, framed around the
//! rays, fitted to the shape of the pane or figure, zoomed and panned; and the clipping of
//! lines to it.

use glam::DVec2;

/// A rectangle of the view's plane, in world units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Lower-left corner (smallest coordinates).
    pub min: DVec2,
    /// Upper-right corner (largest coordinates).
    pub max: DVec2,
}

impl Frame {
    /// The smallest rectangle around the points, with a margin of `margin` of its size on
    /// every side; a frame of side 2 around the origin when there are none.
    pub fn around(points: impl IntoIterator<Item = DVec2>, margin: f64) -> Frame {
        let (mut min, mut max) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for p in points.into_iter().filter(|p| p.is_finite()) {
            min = min.min(p);
            max = max.max(p);
        }
        if !min.is_finite() {
            return Frame {
                min: DVec2::splat(-1.0),
                max: DVec2::ONE,
            };
        }
        // A frame needs some size both ways: rays along one line have none across it.
        let largest = (max - min).max_element().max(1e-9);
        let half = (max - min).max(DVec2::splat(0.1 * largest)) / 2.0 + largest * margin;
        let c = 0.5 * (min + max);
        Frame {
            min: c - half,
            max: c + half,
        }
    }

    /// The same centre, each side at least `side` long.
    pub fn at_least(&self, side: f64) -> Frame {
        let half = (self.size().max(DVec2::splat(side))) / 2.0;
        let c = self.center();
        Frame {
            min: c - half,
            max: c + half,
        }
    }

    /// Width and height, in world units.
    pub fn size(&self) -> DVec2 {
        self.max - self.min
    }

    /// The rectangle's midpoint.
    pub fn center(&self) -> DVec2 {
        0.5 * (self.min + self.max)
    }

    /// Whether `p` lies in the rectangle (edges included).
    pub fn contains(&self, p: DVec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// The same centre, grown in one direction to the aspect `width / height` (in world
    /// units), so that circles stay round.
    pub fn with_aspect(&self, aspect: f64) -> Frame {
        let s = self.size();
        if !(aspect.is_finite() && aspect > 0.0) {
            return *self;
        }
        let half = if s.x / s.y < aspect {
            DVec2::new(s.y * aspect, s.y) / 2.0
        } else {
            DVec2::new(s.x, s.x / aspect) / 2.0
        };
        let c = self.center();
        Frame {
            min: c - half,
            max: c + half,
        }
    }

    /// Zoomed by `zoom` (2 shows half the width) about the centre moved by `pan`, in
    /// fractions of the unzoomed frame's size.
    pub fn zoomed(&self, zoom: f64, pan: DVec2) -> Frame {
        let c = self.center() + pan * self.size();
        let half = self.size() / (2.0 * zoom.max(1e-6));
        Frame {
            min: c - half,
            max: c + half,
        }
    }

    /// The part of the segment a–b inside the frame (Liang–Barsky), if any.
    pub fn clip(&self, a: DVec2, b: DVec2) -> Option<(DVec2, DVec2)> {
        let d = b - a;
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-d.x, a.x - self.min.x),
            (d.x, self.max.x - a.x),
            (-d.y, a.y - self.min.y),
            (d.y, self.max.y - a.y),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
        // Ends inside the frame are kept exactly as they are; a cut end lies on the frame's
        // edge, where rounding may leave it a hair outside: it is put on the edge.
        let at = |t: f64, end: DVec2| {
            if t == 0.0 {
                a
            } else if t == 1.0 {
                end
            } else {
                (a + t * d).clamp(self.min, self.max)
            }
        };
        (t0 <= t1).then(|| (at(t0, a), at(t1, b)))
    }

    /// Where a ray from `from` along `dir` leaves the frame (`from` itself when it is outside
    /// or `dir` is zero in the plane).
    pub fn exit(&self, from: DVec2, dir: DVec2) -> DVec2 {
        if dir.length_squared() == 0.0 || !self.contains(from) {
            // Far enough to leave any frame the point could be seen in.
            return from + dir.normalize_or_zero() * 4.0 * self.size().length();
        }
        let mut t = f64::INFINITY;
        for axis in 0..2 {
            if dir[axis] > 0.0 {
                t = t.min((self.max[axis] - from[axis]) / dir[axis]);
            } else if dir[axis] < 0.0 {
                t = t.min((self.min[axis] - from[axis]) / dir[axis]);
            }
        }
        from + t * dir
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Frame {
        Frame {
            min: DVec2::ZERO,
            max: DVec2::ONE,
        }
    }

    #[test]
    fn clipping_keeps_the_part_inside() {
        let f = unit();
        let (a, b) = f.clip(DVec2::new(-1.0, 0.5), DVec2::new(2.0, 0.5)).unwrap();
        assert_eq!((a, b), (DVec2::new(0.0, 0.5), DVec2::new(1.0, 0.5)));
        assert!(f
            .clip(DVec2::new(-1.0, 2.0), DVec2::new(2.0, 2.0))
            .is_none());
        // A cut end lies in the frame, whatever the rounding of the cut.
        let f = Frame {
            min: DVec2::new(0.1, 0.3),
            max: DVec2::new(0.7, 0.9),
        };
        for k in 1..200 {
            let a = DVec2::new(-1.0 / k as f64, 0.3 + 0.6 / k as f64);
            let b = DVec2::new(3.0, 0.31 + 0.001 * k as f64);
            if let Some((p, q)) = f.clip(a, b) {
                assert!(f.contains(p) && f.contains(q), "{a} {b}: {p} {q}");
            }
        }
        // A diagonal through a corner region that misses the square.
        assert!(f.clip(DVec2::new(1.5, 0.0), DVec2::new(2.0, 2.0)).is_none());
        let inside = (DVec2::new(0.2, 0.3), DVec2::new(0.4, 0.9));
        assert_eq!(f.clip(inside.0, inside.1), Some(inside));
    }

    #[test]
    fn a_ray_leaves_through_the_edge_it_meets_first() {
        let f = unit();
        let e = f.exit(DVec2::new(0.5, 0.5), DVec2::new(1.0, 2.0));
        assert_eq!(e, DVec2::new(0.75, 1.0));
    }

    #[test]
    fn aspect_and_zoom_keep_the_centre() {
        let f = Frame::around([DVec2::ZERO, DVec2::new(4.0, 1.0)], 0.0);
        let g = f.with_aspect(2.0);
        assert_eq!(g.center(), f.center());
        assert!((g.size().x / g.size().y - 2.0).abs() < 1e-12);
        assert!(g.size().x >= f.size().x && g.size().y >= f.size().y);
        let z = g.zoomed(2.0, DVec2::new(0.25, 0.0));
        assert!((z.size().x - g.size().x / 2.0).abs() < 1e-12);
        assert!((z.center().x - (g.center().x + g.size().x / 4.0)).abs() < 1e-12);
    }
}
