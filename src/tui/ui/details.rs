//! The node details pane: where the selected ray starts and goes, what it hit, and the
//! illumination formula with the numbers filled in, term by term, summing to its intensity.

use glam::DVec3;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, swatch, themed, wrap};
use crate::trace::text::{color, node_details, num, vec3};
use crate::trace::{RayKind, RayNode, Termination};
use crate::tui::app::{App, Focus};
use crate::tui::tree;

/// The formula every shaded node follows.
pub const FORMULA: &str = "I = ka·Ia·O + Σℓ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m) + kr·I_r + kt·I_t";

/// The detail lines of a node; a line may carry a colour swatch (drawn after it).
pub fn details_lines(n: &RayNode, max_depth: u32) -> Vec<(String, Option<DVec3>)> {
    let mut out: Vec<(String, Option<DVec3>)> = Vec::new();
    let plain = |s: String| (s, None);
    match n.kind {
        RayKind::Shadow => out.push(plain(format!(
            "shadow ray towards light {} · depth {}",
            n.light.as_deref().unwrap_or("?"),
            n.depth
        ))),
        k => out.push((
            format!(
                "{} ray · depth {} · I = {}",
                k.name(),
                n.depth,
                color(n.color)
            ),
            Some(n.color),
        )),
    }
    out.push(plain(format!("origin    {}", vec3(n.origin))));
    out.push(plain(format!("direction {}", vec3(n.direction))));
    // node_details starts with "ray o → d", said above in two lines.
    for l in node_details(n).into_iter().skip(1) {
        if l.starts_with("ambient") {
            out.push(plain(FORMULA.to_string()));
        }
        out.push(plain(l));
    }
    match n.kind {
        RayKind::Shadow => {
            if let Some(t) = n.t_max {
                out.push(plain(format!("looks for blockers up to t = {}", num(t))));
            }
            out.push(plain(match &n.hit {
                Some(h) => format!(
                    "blocked by {} at t = {}: s = {}",
                    h.object,
                    num(h.t),
                    num(n.shadow.unwrap_or(0.0))
                ),
                None => format!(
                    "nothing in the way: s = {}",
                    num(n.shadow.unwrap_or(1.0))
                ),
            }));
        }
        _ => match n.terminated {
            Some(Termination::Background) => out.push((
                format!("hit nothing: I = background = {}", color(n.color)),
                Some(n.color),
            )),
            Some(Termination::MaxDepth) => out.push(plain(format!(
                "not traced: the path already has {max_depth} rays (the maximum depth); + goes deeper"
            ))),
            Some(Termination::Adaptive) => out.push(plain(format!(
                "not traced: its weight {} is below the adaptive threshold",
                num(n.weight)
            ))),
            Some(Termination::TotalInternalReflection) => out.push(plain(
                "total internal reflection: no light is transmitted; the energy follows the mirror ray"
                    .into(),
            )),
            None => {}
        },
    }
    if let Some(local) = &n.local {
        let mut terms = vec![local.ambient];
        for l in &local.lights {
            terms.push(l.diffuse);
            terms.push(l.specular);
        }
        for c in n.secondary() {
            terms.push(c.coefficient * c.color);
        }
        let sum = terms
            .iter()
            .map(|t| color(*t))
            .collect::<Vec<_>>()
            .join(" + ");
        out.push((
            format!("sum  I = {sum} = {}", color(n.color)),
            Some(n.color),
        ));
    }
    out
}

/// The details pane's lines at a width (wrapped, styled).
pub fn lines(app: &App, width: usize) -> Vec<Line<'static>> {
    let Some(n) = app.selected_node() else {
        return vec![];
    };
    let mut lines: Vec<Line> = Vec::new();
    for (i, (s, sw)) in details_lines(n, app.depth).into_iter().enumerate() {
        let style = if i == 0 {
            Style::new().add_modifier(Modifier::BOLD)
        } else if s.starts_with("I = ka") {
            Style::new().fg(Color::Yellow)
        } else if s.starts_with("sum") {
            Style::new().add_modifier(Modifier::BOLD)
        } else {
            Style::new()
        };
        let style = themed(app, style);
        let sw_w = if sw.is_some() { 3 } else { 0 };
        let parts = wrap(&s, width.saturating_sub(sw_w).max(10));
        let count = parts.len();
        for (j, p) in parts.into_iter().enumerate() {
            let mut spans = vec![Span::styled(p, style)];
            if let (Some(c), true) = (sw, j + 1 == count) {
                spans.push(Span::raw(" "));
                spans.push(swatch(app, c));
            }
            lines.push(Line::from(spans));
        }
    }
    lines
}

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let Some(root) = app.shown_tree() else {
        f.render_widget(pane(app, " details ", Some(Focus::Lower)), area);
        return;
    };
    let at = tree::kinds_of_path(root, &app.selected);
    let title = if at.is_empty() {
        " details · primary ray ".to_string()
    } else {
        format!(" details · {at} ")
    };
    let lines = lines(app, inner(area).width as usize);
    let h = inner(area).height;
    let total = lines.len();
    let (shown, start) = scroll_window(&lines, app.details_scroll, h);
    let mut block = pane(app, title, Some(Focus::Lower));
    if let Some(note) = position_note(start, shown.len(), total) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    f.render_widget(Paragraph::new(shown).block(block), area);
}
