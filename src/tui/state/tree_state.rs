//! Which rays of the tree pane are open and selected, and how far the tree and the selected
//! ray's details are scrolled: state kept apart from the tree it is about (as tui-tree-widget
//! keeps `TreeState` apart from its items), so a retrace replaces the tree and keeps the
//! selection where it still makes sense. Every method is handed the tree shown.

use std::collections::HashSet;

use super::scrolled;
use crate::trace::RayNode;
use crate::tui::msg::Msg;
use crate::tui::tree::{self, NodePath, Row};

#[derive(Default)]
pub struct TreeState {
    open: HashSet<NodePath>,
    selected: NodePath,
    /// The first row of the tree pane.
    offset: usize,
    details_scroll: u16,
}

impl TreeState {
    pub fn selected(&self) -> &[usize] {
        &self.selected
    }

    pub fn offset(&self) -> usize {
        self.offset
    }

    pub fn details_scroll(&self) -> u16 {
        self.details_scroll
    }

    /// The rows of the tree pane, closed rays' descendants left out.
    pub fn rows(&self, root: Option<&RayNode>) -> Vec<Row> {
        root.map_or(vec![], |t| tree::visible_rows(t, &self.open))
    }

    /// The root selected (a new scene).
    pub fn select_root(&mut self) {
        self.selected = vec![];
    }

    /// A new tree: rays open as fits it (all of them when stepping levels), and the selection
    /// kept as far as the new tree has it and shows it.
    pub fn retraced(&mut self, root: &RayNode, all_open: bool) {
        self.open = if all_open {
            tree::all_parents(root)
        } else {
            tree::default_open(root)
        };
        self.selected = tree::valid_prefix(root, &self.selected);
        // A selected node inside a closed parent is shown through its parent.
        while !self.selected.is_empty()
            && !self
                .open
                .contains(&self.selected[..self.selected.len() - 1])
        {
            self.selected.pop();
        }
    }

    /// Tree keys: returns true when the selection moved.
    pub fn update(&mut self, root: Option<&RayNode>, msg: &Msg) -> bool {
        match *msg {
            Msg::Up => self.step(root, -1),
            Msg::Down => self.step(root, 1),
            Msg::Page(d) => self.step(root, 10 * d as i64),
            Msg::Expand => self.expand(root),
            Msg::Collapse => self.collapse(),
            Msg::Toggle => {
                self.toggle(root);
                false
            }
            Msg::ExpandAll => self.expand_all(root),
            _ => false,
        }
    }

    /// Selects a ray; true when that is a change (its details start at the top).
    pub fn select(&mut self, path: NodePath) -> bool {
        if path == self.selected {
            return false;
        }
        self.selected = path;
        self.details_scroll = 0;
        true
    }

    fn selected_node<'a>(&self, root: Option<&'a RayNode>) -> Option<&'a RayNode> {
        tree::node_at(root?, &self.selected)
    }

    fn step(&mut self, root: Option<&RayNode>, delta: i64) -> bool {
        let rows = self.rows(root);
        if rows.is_empty() {
            return false;
        }
        let i = rows
            .iter()
            .position(|r| r.path == self.selected)
            .unwrap_or(0) as i64;
        let j = (i + delta).clamp(0, rows.len() as i64 - 1) as usize;
        self.select(rows[j].path.clone())
    }

    /// Opens the selected ray, or goes to its first child when it is open.
    fn expand(&mut self, root: Option<&RayNode>) -> bool {
        let Some(n) = self.selected_node(root) else {
            return false;
        };
        if n.children.is_empty() {
            return false;
        }
        if self.open.contains(&self.selected) {
            let mut child = self.selected.clone();
            child.push(0);
            self.select(child)
        } else {
            self.open.insert(self.selected.clone());
            false
        }
    }

    /// Closes the selected ray, or goes to its parent when it is closed.
    fn collapse(&mut self) -> bool {
        if self.open.contains(&self.selected) {
            self.open.remove(&self.selected);
            false
        } else if !self.selected.is_empty() {
            let mut parent = self.selected.clone();
            parent.pop();
            self.select(parent)
        } else {
            false
        }
    }

    fn toggle(&mut self, root: Option<&RayNode>) {
        let has_children = self
            .selected_node(root)
            .is_some_and(|n| !n.children.is_empty());
        if !has_children {
            return;
        }
        if !self.open.remove(&self.selected) {
            self.open.insert(self.selected.clone());
        }
    }

    /// Opens every ray, or (all open) goes back to the first level; the selection stays
    /// visible.
    fn expand_all(&mut self, root: Option<&RayNode>) -> bool {
        let Some(t) = root else {
            return false;
        };
        let all = tree::all_parents(t);
        self.open = if self.open == all {
            tree::parents_above(t, 1)
        } else {
            all
        };
        let mut keep = self.selected.clone();
        while !keep.is_empty() && !self.open.contains(&keep[..keep.len() - 1]) {
            keep.pop();
        }
        self.select(keep)
    }

    /// A click on the `row`-th row of the tree's body: selects that ray, or opens or closes
    /// it when it is selected already. True when the selection moved.
    pub fn click(&mut self, root: Option<&RayNode>, row: usize) -> bool {
        let i = self.offset + row;
        let Some(r) = self.rows(root).into_iter().nth(i) else {
            return false;
        };
        if r.path == self.selected {
            self.toggle(root);
            false
        } else {
            self.select(r.path)
        }
    }

    /// Scrolls the tree pane by `delta` rows of a `body`-row pane.
    pub fn scroll_rows(&mut self, root: Option<&RayNode>, delta: i32, body: usize) {
        let max = self.rows(root).len().saturating_sub(body) as i64;
        self.offset = (self.offset as i64 + delta as i64).clamp(0, max) as usize;
    }

    /// Scrolls the tree pane (of `body` rows) so that the selected ray is in sight.
    pub fn keep_selection_visible(&mut self, root: Option<&RayNode>, body: usize) {
        let rows = self.rows(root);
        let body = body.max(1);
        if let Some(i) = rows.iter().position(|r| r.path == self.selected) {
            if i < self.offset {
                self.offset = i;
            } else if i >= self.offset + body {
                self.offset = i + 1 - body;
            }
        }
        self.offset = self.offset.min(rows.len().saturating_sub(body));
    }

    /// Scrolls the selected ray's details by `delta` rows, `max` at most.
    pub fn scroll_details(&mut self, delta: i32, max: u16) {
        self.details_scroll = scrolled(self.details_scroll, delta, max);
    }
}
