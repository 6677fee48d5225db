//! Where every pane goes, as a function of the terminal size and what is open. Drawing and
//! the model (preview resolution, mouse picking, scroll limits) both ask this module, so they
//! always agree.

use ratatui::layout::{Margin, Rect};

/// Terminals at least this wide show the lesson panel as a column of its own.
pub const WIDE: u16 = 120;

/// The tree pane's width on wide terminals: a row four levels deep with its colour.
pub const TREE_WIDTH: u16 = 64;

/// The panes of the scene screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Panes {
    /// The preview's block (border included).
    pub preview: Rect,
    /// The cells the image covers (two pixels per cell, stacked).
    pub image: Rect,
    /// The preview image's size in pixels.
    pub image_px: (u32, u32),
    /// The ray tree.
    pub tree: Rect,
    /// Node details or the CSG panel (absent when a narrow screen gives it to the lesson).
    pub lower: Option<Rect>,
    /// The lesson, when it is open.
    pub lesson: Option<Rect>,
    /// The ray diagram, when it is open.
    pub diagram: Option<Rect>,
    /// The status line.
    pub status: Rect,
    /// The message line.
    pub message: Rect,
}

/// The largest image of this aspect (width / height) that fits `cols` × 2·`rows` pixels.
pub fn fit(cols: u16, rows: u16, aspect: f64) -> (u32, u32) {
    let (max_w, max_h) = (cols as f64, 2.0 * rows as f64);
    if max_w < 1.0 || max_h < 1.0 || !aspect.is_finite() || aspect <= 0.0 {
        return (0, 0);
    }
    let (mut w, mut h) = (max_w, (max_w / aspect).round());
    if h > max_h {
        h = max_h;
        w = (h * aspect).round().min(max_w);
    }
    (w.max(1.0) as u32, h.max(1.0) as u32)
}

/// The status line and `message_rows` message lines at the bottom, and the area above them.
pub fn bottom_lines(area: Rect, message_rows: u16) -> (Rect, Rect, Rect) {
    let main_h = area.height.saturating_sub(1 + message_rows);
    let main = Rect::new(area.x, area.y, area.width, main_h);
    let status = Rect::new(area.x, area.y + main_h, area.width, area.height.min(1));
    let message = Rect::new(
        area.x,
        area.y + main_h + 1,
        area.width,
        area.height.saturating_sub(main_h + 1).min(message_rows),
    );
    (main, status, message)
}

/// The panels open beside the preview and the tree.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Open {
    /// The lesson is open.
    pub lesson: bool,
    /// The ray diagram is open.
    pub diagram: bool,
}

/// The scene screen: preview and tree on top, details (or CSG) below, the lesson beside
/// (wide screens) or in place of the details (narrow ones), status and message lines at the
/// bottom. The diagram shares the bottom with the details (or the lesson), on its right; on a
/// wide screen with the lesson open it takes the top of the lesson's column instead. On a
/// wide screen the preview gives up width (down to two thirds of what it would take) so that
/// the tree pane is `TREE_WIDTH` wide: deep rows with their colours fit. The tree shown does
/// not change the layout, so picking a pixel never renders the preview again.
pub fn scene_panes(area: Rect, aspect: f64, open: Open, message_rows: u16) -> Panes {
    let (main, status, message) = bottom_lines(area, message_rows);
    let wide = area.width >= WIDE;
    let (left, side) = if open.lesson && wide {
        let lw = (area.width * 2 / 5).max(40);
        let left = Rect::new(main.x, main.y, main.width - lw, main.height);
        let side = Rect::new(main.x + left.width, main.y, lw, main.height);
        (left, Some(side))
    } else {
        (main, None)
    };
    let top_h = left.height.div_ceil(2);
    let top = Rect::new(left.x, left.y, left.width, top_h);
    let bottom = Rect::new(left.x, left.y + top_h, left.width, left.height - top_h);
    let inner_h = top_h.saturating_sub(2);
    let wanted = ((2.0 * inner_h as f64 * aspect).round() as u16).saturating_add(2);
    let cap = if side.is_some() {
        left.width * 2 / 5
    } else {
        left.width * 3 / 5
    };
    let full = wanted.min(cap);
    let tree_width = if wide { TREE_WIDTH } else { 0 };
    let room = left.width.saturating_sub(tree_width);
    let pw = full.min(room.max(full * 2 / 3)).max(left.width.min(6));
    let preview = Rect::new(top.x, top.y, pw, top_h);
    let tree = Rect::new(top.x + pw, top.y, top.width - pw, top_h);
    let inner = preview.inner(Margin::new(1, 1));
    let (iw, ih) = fit(inner.width, inner.height, aspect);
    let cells_h = ih.div_ceil(2) as u16;
    let image = Rect::new(
        inner.x + (inner.width - iw as u16) / 2,
        inner.y + (inner.height - cells_h) / 2,
        iw as u16,
        cells_h,
    );
    let (mut lower, mut lesson) = match (open.lesson, side) {
        (true, None) => (None, Some(bottom)),
        (_, side) => (Some(bottom), side),
    };
    let mut diagram = None;
    if open.diagram {
        match side {
            Some(col) => {
                let dh = col.height * 11 / 20;
                diagram = Some(Rect::new(col.x, col.y, col.width, dh));
                lesson = Some(Rect::new(col.x, col.y + dh, col.width, col.height - dh));
            }
            None => {
                // The details (or the lesson) keep 9/20 of the width: their lines wrap.
                let lw = bottom.width * 9 / 20;
                let left_part = Rect::new(bottom.x, bottom.y, lw, bottom.height);
                diagram = Some(Rect::new(
                    bottom.x + lw,
                    bottom.y,
                    bottom.width - lw,
                    bottom.height,
                ));
                if lower.is_some() {
                    lower = Some(left_part);
                } else {
                    lesson = Some(left_part);
                }
            }
        }
    }
    Panes {
        preview,
        image,
        image_px: (iw, ih),
        tree,
        lower,
        lesson,
        diagram,
        status,
        message,
    }
}

/// The lesson list screen: the list on the left, the selected lesson's summary on the right.
pub fn list_panes(area: Rect) -> (Rect, Rect, Rect, Rect) {
    let (main, status, message) = bottom_lines(area, 1);
    let lw = (main.width * 3 / 5).max(main.width.min(36));
    let list = Rect::new(main.x, main.y, lw, main.height);
    let info = Rect::new(main.x + lw, main.y, main.width - lw, main.height);
    (list, info, status, message)
}

/// The inner area of a bordered pane.
pub fn inner(r: Rect) -> Rect {
    r.inner(Margin::new(1, 1))
}

/// The first row shown of a list of which `selected` must be visible in `height` rows.
pub fn list_offset(selected: usize, height: usize) -> usize {
    if height == 0 {
        0
    } else {
        (selected + 1).saturating_sub(height)
    }
}

/// The cell of the image that shows pixel (x, y) of a `w` × `h` scene: the one a click picks
/// that pixel from (`cell_pixel`) where there is one (a preview larger than the image shows a
/// pixel over several cells, and a cell's edges need not fall on the pixel's), else the cell
/// that holds the pixel's centre (a smaller preview shows several pixels in one cell).
pub fn pixel_cell(panes: &Panes, (w, h): (u32, u32), (x, y): (u32, u32)) -> Option<(u16, u16)> {
    let (pw, ph) = panes.image_px;
    if pw == 0 || ph == 0 || w == 0 || h == 0 {
        return None;
    }
    let r = panes.image;
    let px = ((x as f64 + 0.5) * pw as f64 / w as f64) as u16;
    let py = ((y as f64 + 0.5) * ph as f64 / h as f64) as u16;
    let centre = (r.x + px.min(pw as u16 - 1), r.y + py.min(ph as u16 - 1) / 2);
    let picks = |(c, row): (u16, u16)| cell_pixel(panes, (w, h), c, row) == Some((x, y));
    let near = |v: u16| [v, v.saturating_sub(1), v.saturating_add(1)];
    let mut cells = near(centre.0)
        .into_iter()
        .flat_map(|c| near(centre.1).map(|row| (c, row)));
    Some(cells.find(|&cell| picks(cell)).unwrap_or(centre))
}

/// The scene pixel under a cell of the image (the centre of the cell's two pixels).
pub fn cell_pixel(panes: &Panes, (w, h): (u32, u32), col: u16, row: u16) -> Option<(u32, u32)> {
    let r = panes.image;
    let (pw, ph) = panes.image_px;
    if pw == 0 || ph == 0 || col < r.x || row < r.y || col >= r.right() || row >= r.bottom() {
        return None;
    }
    let px = (col - r.x) as f64 + 0.5;
    let py = (2.0 * (row - r.y) as f64 + 1.0).min(ph as f64 - 0.5);
    let x = ((px * w as f64 / pw as f64) as u32).min(w - 1);
    let y = ((py * h as f64 / ph as f64) as u32).min(h - 1);
    Some((x, y))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_keeps_the_aspect() {
        assert_eq!(fit(40, 10, 1.0), (20, 20));
        assert_eq!(fit(40, 30, 4.0 / 3.0), (40, 30));
        assert_eq!(fit(0, 10, 1.0), (0, 0));
    }

    #[test]
    fn panes_do_not_overlap_and_the_tree_gets_the_width_it_needs() {
        for (w, h) in [(80, 24), (100, 30), (160, 48)] {
            for lesson in [false, true] {
                for diagram in [false, true] {
                    let open = Open { lesson, diagram };
                    let p = scene_panes(Rect::new(0, 0, w, h), 4.0 / 3.0, open, 1);
                    let rects: Vec<Rect> =
                        [Some(p.preview), Some(p.tree), p.lower, p.lesson, p.diagram]
                            .into_iter()
                            .flatten()
                            .collect();
                    for (i, a) in rects.iter().enumerate() {
                        assert!(a.width > 0 && a.height > 0, "{w}×{h} {open:?}: {a:?}");
                        for b in &rects[i + 1..] {
                            assert!(!a.intersects(*b), "{w}×{h} {open:?}: {a:?} and {b:?}");
                        }
                    }
                    assert_eq!(p.diagram.is_some(), diagram);
                    assert_eq!(p.lesson.is_some(), lesson);
                }
            }
        }
        // With the lesson open on a wide screen the tree still gets its width.
        let open = Open {
            lesson: true,
            diagram: false,
        };
        let p = scene_panes(Rect::new(0, 0, 160, 48), 4.0 / 3.0, open, 1);
        assert!(p.tree.width >= TREE_WIDTH, "{:?}", p.tree);
    }

    #[test]
    fn picking_a_cell_and_marking_a_pixel_agree() {
        let p = scene_panes(Rect::new(0, 0, 80, 24), 161.0 / 121.0, Open::default(), 1);
        for (x, y) in [(0, 0), (80, 60), (160, 120), (13, 77)] {
            let (c, r) = pixel_cell(&p, (161, 121), (x, y)).unwrap();
            let (x2, y2) = cell_pixel(&p, (161, 121), c, r).unwrap();
            assert_eq!(pixel_cell(&p, (161, 121), (x2, y2)), Some((c, r)));
        }
    }

    /// A preview larger than the image (a 61 × 61 scene in a wide terminal, a 3 × 2 one
    /// anywhere) shows each pixel over several cells: clicking the cell that marks a pixel
    /// picks that pixel, for every pixel a click can pick, so clicking the marker again and
    /// again stays put.
    #[test]
    fn clicking_the_marker_of_a_pixel_picks_it_in_a_preview_larger_than_the_image() {
        for (area, (w, h)) in [
            ((200, 90), (61, 61)),
            ((140, 44), (3, 2)),
            ((80, 24), (7, 5)),
        ] {
            let p = scene_panes(
                Rect::new(0, 0, area.0, area.1),
                w as f64 / h as f64,
                Open::default(),
                1,
            );
            let r = p.image;
            let pickable: std::collections::BTreeSet<(u32, u32)> = (r.x..r.right())
                .flat_map(|c| (r.y..r.bottom()).map(move |row| (c, row)))
                .filter_map(|(c, row)| cell_pixel(&p, (w, h), c, row))
                .collect();
            assert!(pickable.len() > 1, "{area:?}");
            for &(x, y) in &pickable {
                let (c, row) = pixel_cell(&p, (w, h), (x, y)).unwrap();
                assert_eq!(
                    cell_pixel(&p, (w, h), c, row),
                    Some((x, y)),
                    "{area:?}, {w}×{h}: pixel {x},{y} marked at {c},{row}"
                );
            }
        }
    }
}
