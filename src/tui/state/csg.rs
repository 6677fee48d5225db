//! The CSG panel: for every ray of the picked pixel's tree, the segment list at every node of
//! every object it meets, pruned nodes included, and why the others are not shown (culled by
//! a bounding box, or missed); it scrolls to the selected ray's section. Like `raytree csg
//! --all`, it can show every object evaluated whole instead.

use ratatui::layout::Rect;

use super::{max_scroll, scrolled};
use crate::geometry::Ray;
use crate::scene::Scene;
use crate::trace::{text, RayNode, Termination};
use crate::tui::layout::inner;
use crate::tui::tree::{self, NodePath};
use crate::tui::wrap::wrap;

/// The CSG panel lists the segment lists of at most this many rays of a tree.
pub const CSG_MAX_RAYS: usize = 64;

/// A line of the CSG panel, tagged with the ray (tree node) it belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CsgLine {
    pub node: NodePath,
    pub header: bool,
    pub text: String,
}

/// How a row of the CSG panel is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgKind {
    /// The first line of a ray's section.
    Header,
    /// A node or object skipped (pruned, culled) or missed.
    Pruned,
    Plain,
}

/// A row of the CSG panel; `marked` on the first row of the selected ray's section.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CsgRow {
    pub text: String,
    pub kind: CsgKind,
    pub marked: bool,
}

#[derive(Default)]
pub struct CsgPanel {
    shown: bool,
    /// Every object, evaluated whole without bounding boxes (`raytree csg --all`).
    all: bool,
    lines: Vec<CsgLine>,
    scroll: u16,
}

impl CsgPanel {
    pub fn shown(&self) -> bool {
        self.shown
    }

    pub fn lines(&self) -> &[CsgLine] {
        &self.lines
    }

    pub fn scroll(&self) -> u16 {
        self.scroll
    }

    /// Shows or hides the panel; true when it is shown now (and wants `compute`).
    pub fn toggle(&mut self) -> bool {
        self.shown = !self.shown;
        self.shown
    }

    pub fn hide(&mut self) {
        self.shown = false;
    }

    /// Every object evaluated whole, or only those the rays meet through the boxes.
    pub fn all(&self) -> bool {
        self.all
    }

    /// Switches between every object and the objects met; shows the panel (it wants
    /// `compute`).
    pub fn toggle_all(&mut self) {
        self.all = !self.all;
        self.shown = true;
    }

    /// No segment list at all: no ray meets an object.
    pub fn is_empty(&self) -> bool {
        self.lines.iter().all(|l| l.header) || self.lines.is_empty()
    }

    /// The segment lists of every ray of `root` (the tree shown), scrolled to the selected
    /// ray's section in the lower pane.
    pub fn compute(
        &mut self,
        scene: Option<&Scene>,
        root: Option<&RayNode>,
        selected: &[usize],
        pane: Option<Rect>,
    ) {
        let (Some(scene), Some(root)) = (scene, root) else {
            self.lines.clear();
            return;
        };
        let mut lines = Vec::new();
        // The size of the tree's numbers, below whose rounding a coordinate reads 0.
        let scale = text::tree_scale(root);
        let paths = tree::ray_paths(root);
        let more = paths.len().saturating_sub(CSG_MAX_RAYS);
        for path in paths.into_iter().take(CSG_MAX_RAYS) {
            let n = tree::node_at(root, &path).expect("path from the tree");
            if matches!(
                n.terminated,
                Some(Termination::MaxDepth) | Some(Termination::Adaptive)
            ) {
                continue;
            }
            let ray = Ray::new(n.origin, n.direction);
            let at = tree::kinds_of_path(root, &path);
            let name = if at.is_empty() {
                "primary ray".to_string()
            } else {
                format!("{at} ray")
            };
            lines.push(CsgLine {
                node: path.clone(),
                header: true,
                text: format!(
                    "{name} {} → {}",
                    text::ray_origin(n, scale),
                    text::vec3(ray.dir)
                ),
            });
            let survey = text::csg_survey(scene, &ray, self.all);
            let mut line = |text: String| {
                lines.push(CsgLine {
                    node: path.clone(),
                    header: false,
                    text,
                })
            };
            if survey.met.is_empty() {
                line("  meets no object".into());
            }
            for m in &survey.met {
                line(format!("  object {}", m.name));
                for l in text::csg_trace_at(scene, &ray, &m.trace, scale).lines() {
                    line(format!("    {l}"));
                }
                line(format!("    → {}", m.verdict(&ray)));
            }
            for l in &survey.unmet {
                line(format!("  {l}"));
            }
            if !survey.met.is_empty() {
                line(format!("  {}", survey.nearest_line(&ray)));
            }
        }
        if more > 0 {
            lines.push(CsgLine {
                node: vec![usize::MAX],
                header: false,
                text: format!("… and {more} more rays (raytree csg --ray shows any of them)"),
            });
        }
        self.lines = lines;
        self.follow(selected, pane);
    }

    /// Scrolls to the selected ray's section.
    pub fn follow(&mut self, selected: &[usize], pane: Option<Rect>) {
        let row = pane
            .and_then(|r| self.rows(selected, inner(r).width as usize).1)
            .unwrap_or(0) as u16;
        self.scroll = row.min(self.max_scroll(selected, pane));
    }

    /// Scrolls by `delta` rows in the lower pane.
    pub fn scroll_by(&mut self, delta: i32, selected: &[usize], pane: Option<Rect>) {
        let max = self.max_scroll(selected, pane);
        self.scroll = scrolled(self.scroll, delta, max);
    }

    /// How far the panel can scroll in the lower pane (none without the pane).
    pub fn max_scroll(&self, selected: &[usize], pane: Option<Rect>) -> u16 {
        pane.map_or(0, |r| {
            let i = inner(r);
            max_scroll(self.rows(selected, i.width as usize).0.len(), i.height)
        })
    }

    /// The section that belongs to the selected ray (or to the ray a shadow ray leaves from).
    fn section(&self, selected: &[usize]) -> NodePath {
        let mut section = selected.to_vec();
        while !section.is_empty() && !self.lines.iter().any(|l| l.header && l.node == section) {
            section.pop();
        }
        section
    }

    /// The panel's rows at a width (two cells go to the mark), and the row where the selected
    /// ray's section starts.
    pub fn rows(&self, selected: &[usize], width: usize) -> (Vec<CsgRow>, Option<usize>) {
        let section = self.section(selected);
        let mut rows = Vec::new();
        let mut start = None;
        for l in &self.lines {
            let mine = l.node == section;
            if l.header && mine && start.is_none() {
                start = Some(rows.len());
            }
            let kind = if l.header {
                CsgKind::Header
            } else if [
                "pruned:",
                "not evaluated:",
                "culled:",
                "misses",
                "meets none",
            ]
            .iter()
            .any(|w| l.text.contains(w))
            {
                CsgKind::Pruned
            } else {
                CsgKind::Plain
            };
            for (j, text) in wrap(&l.text, width.saturating_sub(2).max(10))
                .into_iter()
                .enumerate()
            {
                rows.push(CsgRow {
                    text,
                    kind,
                    marked: l.header && mine && j == 0,
                });
            }
        }
        if rows.is_empty() {
            rows.push(CsgRow {
                text: "no rays".into(),
                kind: CsgKind::Plain,
                marked: false,
            });
        }
        (rows, start)
    }
}
