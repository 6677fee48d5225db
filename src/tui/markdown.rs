//! A lesson README laid out for a pane of a given width: parsed as Markdown (pulldown-cmark),
//! paragraphs and list items word-wrapped (textwrap's first-fit over styled words), tables
//! aligned in columns, shell commands wrapped under their first line, and every other code
//! block (a figure drawn in characters, a listing) kept whole, line for line, for the pane to
//! show through a window that moves sideways. Each row is a list of spans tagged with how they
//! are drawn; the lesson panel scrolls through the rows and the drawing code styles them.

use pulldown_cmark::{Alignment, CodeBlockKind, Event, Options, Parser, Tag, TagEnd};
use textwrap::core::Fragment;
use textwrap::wrap_algorithms::wrap_first_fit;

use super::wrap::{width as cells, wrap_hang};

/// How a piece of a README is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Md {
    Heading,
    /// A line of a shell command, wrapped to the pane.
    Code,
    /// A line of any other code block: kept whole, never wrapped (a figure must not break).
    Figure,
    Text,
    /// A paragraph that starts "Answer (": the worked solution's result.
    Answer,
    Strong,
    Emphasis,
    /// `code` within a sentence.
    InlineCode,
    Link,
    /// Table borders and quote bars.
    Rule,
}

/// One row of the pane: its spans, left to right.
pub type Row = Vec<(String, Md)>;

/// The README laid out in rows at most `width` cells wide (a word longer than a row is cut),
/// except the rows of figures, which are as wide as they were written (see `window`).
pub fn markdown(text: &str, width: usize) -> Vec<Row> {
    let mut w = Writer {
        width: width.max(4),
        ..Writer::default()
    };
    let options = Options::ENABLE_TABLES | Options::ENABLE_STRIKETHROUGH;
    for event in Parser::new_ext(text, options) {
        w.event(event);
    }
    w.flush(None);
    while w.rows.last().is_some_and(|r| r.is_empty()) {
        w.rows.pop();
    }
    w.rows
}

/// The languages of fenced code blocks that are shell commands: wrapped like prose, since a
/// command reads as well on two rows and a figure does not.
const SHELLS: [&str; 5] = ["sh", "shell", "bash", "console", "zsh"];

/// How far the widest row sticks out of a pane `width` cells wide (0 when every row fits):
/// how far the window over the figures can move.
pub fn overhang(rows: &[Row], width: usize) -> usize {
    rows.iter()
        .map(|r| r.iter().map(|(s, _)| cells(s)).sum::<usize>())
        .max()
        .unwrap_or(0)
        .saturating_sub(width)
}

/// A row as the pane shows it: the rows of figures seen through a window `width` cells wide
/// that starts `pan` cells into the figure, with `‹` and `›` where more of it is hidden;
/// other rows as they are.
pub fn window(row: &Row, pan: usize, width: usize) -> Row {
    if !row.iter().any(|(_, m)| *m == Md::Figure) {
        return row.clone();
    }
    let lead: usize = row
        .iter()
        .filter(|(_, m)| *m != Md::Figure)
        .map(|(s, _)| cells(s))
        .sum();
    let room = width.saturating_sub(lead);
    row.iter()
        .map(|(s, m)| match m {
            Md::Figure => (window_text(s, pan, room), Md::Figure),
            _ => (s.clone(), *m),
        })
        .collect()
}

/// The cells `pan .. pan + room` of a line, the first and last of them turned into `‹`, `›`
/// when the line goes on beyond them with something more than spaces.
fn window_text(line: &str, pan: usize, room: usize) -> String {
    let chars: Vec<(char, usize)> = line
        .chars()
        .map(|c| (c, cells(c.encode_utf8(&mut [0; 4]))))
        .collect();
    let mut at = 0;
    let (mut before, mut shown, mut after) = (String::new(), vec![], String::new());
    for (c, w) in chars {
        if at < pan {
            before.push(c);
        } else if at + w <= pan + room {
            shown.push(c);
        } else {
            after.push(c);
        }
        at += w;
    }
    if room > 1 && !after.trim().is_empty() {
        if let Some(last) = shown.last_mut() {
            *last = '›';
        }
    }
    if room > 1 && !before.trim().is_empty() && !shown.is_empty() {
        shown[0] = '‹';
    }
    shown.into_iter().collect::<String>().trim_end().to_string()
}

/// A word: its pieces, each with its style (`**bold**,` is two pieces, one word).
#[derive(Debug, Clone)]
struct Word {
    pieces: Vec<(String, Md)>,
    width: usize,
}

impl Fragment for Word {
    fn width(&self) -> f64 {
        self.width as f64
    }
    fn whitespace_width(&self) -> f64 {
        1.0
    }
    fn penalty_width(&self) -> f64 {
        0.0
    }
}

#[derive(Default)]
struct Writer {
    width: usize,
    rows: Vec<Row>,
    /// The inline text of the block being read.
    spans: Vec<(String, Md)>,
    /// Emphasis, strong, link: the innermost wins.
    styles: Vec<Md>,
    /// Each open list: the next item's number (None for bullets), and the width of its
    /// current item's marker, under which the item's text hangs.
    lists: Vec<(Option<u64>, usize)>,
    /// The marker of the list item whose first line is next ("- ", "2. ").
    marker: Option<String>,
    quotes: usize,
    heading: bool,
    /// The code block being read, and whether it wraps (a shell command).
    code: Option<(String, bool)>,
    /// Rows of cells of the table being read.
    table: Option<Vec<Vec<String>>>,
    aligns: Vec<Alignment>,
    links: Vec<String>,
}

impl Writer {
    fn style(&self) -> Md {
        self.styles.last().copied().unwrap_or(Md::Text)
    }

    fn blank(&mut self) {
        if self.rows.last().is_some_and(|r| !r.is_empty()) {
            self.rows.push(vec![]);
        }
    }

    /// What starts every row of the current block: quote bars, then the list indentation.
    fn indent(&self) -> (String, String) {
        let bars = "│ ".repeat(self.quotes);
        let indent = self.lists.iter().map(|(_, w)| *w).sum::<usize>();
        (bars, " ".repeat(indent))
    }

    fn event(&mut self, event: Event) {
        match event {
            Event::Start(tag) => self.start(tag),
            Event::End(tag) => self.end(tag),
            Event::Text(t) => {
                if let Some((code, _)) = &mut self.code {
                    code.push_str(&t);
                } else if let Some(cell) = self.cell() {
                    cell.push_str(&t);
                } else {
                    let style = self.style();
                    self.spans.push((t.to_string(), style));
                }
            }
            Event::Code(t) => {
                if let Some(cell) = self.cell() {
                    cell.push_str(&t);
                } else {
                    self.spans.push((t.to_string(), Md::InlineCode));
                }
            }
            Event::SoftBreak => self.spans.push((" ".into(), Md::Text)),
            Event::HardBreak => self.flush(None),
            Event::Rule => {
                self.flush(None);
                self.rows.push(vec![("─".repeat(self.width), Md::Rule)]);
                self.blank();
            }
            Event::InlineMath(t) | Event::DisplayMath(t) => {
                self.spans.push((t.to_string(), Md::InlineCode))
            }
            Event::TaskListMarker(done) => self
                .spans
                .push((if done { "[x] " } else { "[ ] " }.into(), Md::Text)),
            Event::Html(_) | Event::InlineHtml(_) | Event::FootnoteReference(_) => {}
        }
    }

    fn cell(&mut self) -> Option<&mut String> {
        self.table.as_mut()?.last_mut()?.last_mut()
    }

    fn start(&mut self, tag: Tag) {
        match tag {
            Tag::Heading { .. } => {
                self.flush(None);
                self.heading = true;
            }
            Tag::List(first) => {
                self.flush(None);
                self.lists.push((first, 0));
            }
            Tag::Item => {
                self.flush(None);
                if let Some((number, width)) = self.lists.last_mut() {
                    let marker = match number {
                        Some(n) => {
                            *n += 1;
                            format!("{}. ", *n - 1)
                        }
                        None => "• ".into(),
                    };
                    *width = cells(&marker);
                    self.marker = Some(marker);
                }
            }
            Tag::BlockQuote(_) => {
                self.flush(None);
                self.quotes += 1;
            }
            Tag::CodeBlock(kind) => {
                self.flush(None);
                let shell = match kind {
                    CodeBlockKind::Fenced(lang) => SHELLS.contains(&lang.trim()),
                    CodeBlockKind::Indented => false,
                };
                self.code = Some((String::new(), shell));
            }
            Tag::Table(aligns) => {
                self.flush(None);
                self.table = Some(vec![]);
                self.aligns = aligns;
            }
            Tag::TableHead | Tag::TableRow => {
                if let Some(t) = &mut self.table {
                    t.push(vec![]);
                }
            }
            Tag::TableCell => {
                if let Some(row) = self.table.as_mut().and_then(|t| t.last_mut()) {
                    row.push(String::new());
                }
            }
            Tag::Emphasis => self.styles.push(Md::Emphasis),
            Tag::Strong => self.styles.push(Md::Strong),
            Tag::Link { dest_url, .. } => {
                self.styles.push(Md::Link);
                self.links.push(dest_url.to_string());
            }
            _ => {}
        }
    }

    fn end(&mut self, tag: TagEnd) {
        match tag {
            TagEnd::Paragraph => {
                self.flush(None);
                if self.lists.is_empty() {
                    self.blank();
                }
            }
            TagEnd::Heading(_) => {
                self.flush(Some(Md::Heading));
                self.heading = false;
                self.blank();
            }
            TagEnd::Item => self.flush(None),
            TagEnd::List(_) => {
                self.flush(None);
                self.lists.pop();
                if self.lists.is_empty() {
                    self.blank();
                }
            }
            TagEnd::BlockQuote(_) => {
                self.flush(None);
                self.quotes -= 1;
                self.blank();
            }
            TagEnd::CodeBlock => {
                let (code, shell) = self.code.take().unwrap_or_default();
                let (bars, indent) = self.indent();
                for line in code.lines() {
                    let mut row = vec![];
                    if !bars.is_empty() {
                        row.push((bars.clone(), Md::Rule));
                    }
                    if !shell {
                        row.push((format!("{indent}{line}"), Md::Figure));
                        self.rows.push(row);
                        continue;
                    }
                    let room = self.width.saturating_sub(cells(&bars));
                    for (k, l) in wrap_hang(&format!("{indent}{line}"), room, "    ")
                        .into_iter()
                        .enumerate()
                    {
                        if k == 0 {
                            row.push((l, Md::Code));
                            self.rows.push(std::mem::take(&mut row));
                        } else {
                            self.rows.push(vec![(l, Md::Code)]);
                        }
                    }
                }
                if self.lists.is_empty() {
                    self.blank();
                }
            }
            TagEnd::Table => {
                let table = self.table.take().unwrap_or_default();
                self.table_rows(&table);
                self.blank();
            }
            TagEnd::Emphasis | TagEnd::Strong => {
                self.styles.pop();
            }
            TagEnd::Link => {
                self.styles.pop();
                let dest = self.links.pop().unwrap_or_default();
                let shown: String = self.spans.iter().map(|(s, _)| s.as_str()).collect();
                // A terminal cannot follow a link: say where it goes, unless its text does.
                if !dest.is_empty() && !dest.starts_with('#') && !shown.ends_with(&dest) {
                    self.spans.push((format!(" ({dest})"), Md::Link));
                }
            }
            _ => {}
        }
    }

    /// The columns of a table padded to their widest cell, separated by bars, the header row
    /// strong and underlined; a table wider than the pane is wrapped line by line.
    fn table_rows(&mut self, table: &[Vec<String>]) {
        let columns = table.iter().map(Vec::len).max().unwrap_or(0);
        let widths: Vec<usize> = (0..columns)
            .map(|c| {
                table
                    .iter()
                    .filter_map(|r| r.get(c))
                    .map(|s| cells(s.trim()))
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let (bars, indent) = self.indent();
        let room = self.width.saturating_sub(cells(&bars));
        for (i, row) in table.iter().enumerate() {
            let line: Vec<String> = (0..columns)
                .map(|c| {
                    let cell = row.get(c).map_or("", |s| s.trim());
                    let pad = widths[c] - cells(cell);
                    let (left, right) = match self.aligns.get(c) {
                        Some(Alignment::Right) => (pad, 0),
                        Some(Alignment::Center) => (pad / 2, pad - pad / 2),
                        _ => (0, pad),
                    };
                    format!("{}{cell}{}", " ".repeat(left), " ".repeat(right))
                })
                .collect();
            let kind = if i == 0 { Md::Strong } else { Md::Text };
            let text = format!("{indent}{}", line.join(" │ ").trim_end());
            for l in wrap_hang(&text, room, "    ") {
                self.rows.push(vec![(bars.clone(), Md::Rule), (l, kind)]);
            }
            if i == 0 {
                let rule: Vec<String> = widths.iter().map(|w| "─".repeat(*w)).collect();
                let rule = format!("{indent}{}", rule.join("─┼─"));
                let rule: String = rule.chars().take(room).collect();
                self.rows
                    .push(vec![(bars.clone(), Md::Rule), (rule, Md::Rule)]);
            }
        }
        for r in self.rows.iter_mut() {
            r.retain(|(s, _)| !s.is_empty());
        }
    }

    /// Lays out the inline text read so far as word-wrapped rows (`kind` overrides the
    /// spans' own styles, as for a heading).
    fn flush(&mut self, kind: Option<Md>) {
        let spans = std::mem::take(&mut self.spans);
        let text: String = spans.iter().map(|(s, _)| s.as_str()).collect();
        if text.trim().is_empty() {
            return;
        }
        let answer = text.trim_start().starts_with("Answer (");
        let restyle = |m: Md| match (kind, m) {
            (Some(k), _) => k,
            (None, Md::Text | Md::Strong) if answer => Md::Answer,
            _ => m,
        };
        let (bars, indent) = self.indent();
        let (first, hang) = match self.marker.take() {
            Some(marker) if !self.lists.is_empty() => {
                let outer: usize = self.lists.iter().rev().skip(1).map(|(_, w)| *w).sum();
                (format!("{}{marker}", " ".repeat(outer)), indent)
            }
            _ => (indent.clone(), indent),
        };
        let room = self.width.saturating_sub(cells(&bars));
        let words = words(&spans, room.saturating_sub(cells(&hang)).max(1), restyle);
        let widths = [
            room.saturating_sub(cells(&first)) as f64,
            room.saturating_sub(cells(&hang)) as f64,
        ];
        for (k, line) in wrap_first_fit(&words, &widths).into_iter().enumerate() {
            let mut row: Row = vec![];
            if !bars.is_empty() {
                row.push((bars.clone(), Md::Rule));
            }
            let lead = if k == 0 { &first } else { &hang };
            if !lead.is_empty() {
                row.push((lead.clone(), Md::Text));
            }
            for (j, word) in line.iter().enumerate() {
                if j > 0 {
                    // A space inside styled text (`t = 2`) keeps the style.
                    let before = line[j - 1].pieces.last().map(|p| p.1);
                    let after = word.pieces.first().map(|p| p.1);
                    let style = if before == after {
                        before.unwrap_or(Md::Text)
                    } else {
                        Md::Text
                    };
                    row.push((" ".into(), style));
                }
                row.extend(word.pieces.iter().cloned());
            }
            self.rows.push(merged(row));
        }
    }
}

/// Neighbouring spans of one style joined.
fn merged(row: Row) -> Row {
    let mut out: Row = vec![];
    for (text, style) in row {
        match out.last_mut() {
            Some((s, m)) if *m == style => s.push_str(&text),
            _ => out.push((text, style)),
        }
    }
    out
}

/// The words of styled text, split at spaces; a word wider than `max` cells is cut into
/// pieces that fit.
fn words(spans: &[(String, Md)], max: usize, restyle: impl Fn(Md) -> Md) -> Vec<Word> {
    let mut out = vec![];
    let mut cur = Word {
        pieces: vec![],
        width: 0,
    };
    let end = |cur: &mut Word, out: &mut Vec<Word>| {
        if cur.width > 0 {
            out.push(std::mem::replace(
                cur,
                Word {
                    pieces: vec![],
                    width: 0,
                },
            ));
        }
    };
    for (text, style) in spans {
        let style = restyle(*style);
        for c in text.chars() {
            if c.is_whitespace() {
                end(&mut cur, &mut out);
                continue;
            }
            let w = cells(c.encode_utf8(&mut [0; 4]));
            if cur.width + w > max {
                end(&mut cur, &mut out);
            }
            match cur.pieces.last_mut() {
                Some((s, m)) if *m == style => s.push(c),
                _ => cur.pieces.push((c.to_string(), style)),
            }
            cur.width += w;
        }
    }
    end(&mut cur, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::{markdown, overhang, window, Md};

    fn text(rows: &[super::Row]) -> Vec<String> {
        rows.iter()
            .map(|r| r.iter().map(|(s, _)| s.as_str()).collect())
            .collect()
    }

    #[test]
    fn emphasis_and_code_are_styled_not_shown_as_markers() {
        let rows = markdown("A **bold** and *soft* `t = 2` word.", 80);
        assert_eq!(text(&rows), vec!["A bold and soft t = 2 word."]);
        let styles: Vec<(String, Md)> = rows[0].clone();
        assert!(styles.contains(&("bold".into(), Md::Strong)));
        assert!(styles.contains(&("soft".into(), Md::Emphasis)));
        assert!(styles.contains(&("t = 2".into(), Md::InlineCode)));
    }

    #[test]
    fn list_items_wrap_under_their_text() {
        let rows = markdown("1. one two three four\n2. five\n\n- six seven", 12);
        assert_eq!(
            text(&rows),
            vec![
                "1. one two",
                "   three",
                "   four",
                "2. five",
                "",
                "• six seven"
            ]
        );
    }

    #[test]
    fn tables_line_up_in_columns() {
        let rows = markdown("| a | long b |\n|---|---|\n| 123 | x |\n", 40);
        assert_eq!(text(&rows), vec!["a   │ long b", "────┼───────", "123 │ x"]);
    }

    #[test]
    fn numbers_align_right_where_the_table_says() {
        let rows = markdown("| a | n |\n|---|--:|\n| x | 1.5 |\n| y | 10 |\n", 40);
        assert_eq!(
            text(&rows),
            vec!["a │   n", "──┼────", "x │ 1.5", "y │  10"]
        );
    }

    #[test]
    fn links_say_where_they_go() {
        let rows = markdown("See [the tracer](src/trace/whitted.rs).", 80);
        assert_eq!(text(&rows), vec!["See the tracer (src/trace/whitted.rs)."]);
    }

    #[test]
    fn figures_stay_whole_and_commands_wrap() {
        let md = "```\n+----------------------+\n|        figure        |\n```\n\n\
                  ```sh\nraytree render scene.yaml -o out.png\n```\n";
        let rows = markdown(md, 20);
        assert_eq!(
            text(&rows),
            vec![
                "+----------------------+",
                "|        figure        |",
                "",
                "raytree render",
                "    scene.yaml -o",
                "    out.png"
            ]
        );
        assert!(rows[0].iter().all(|(_, m)| *m == Md::Figure));
        assert!(rows[3].iter().all(|(_, m)| *m == Md::Code));
        assert_eq!(overhang(&rows, 20), 4, "24 cells in a pane of 20");
        assert_eq!(overhang(&rows, 30), 0);
    }

    #[test]
    fn a_window_shows_part_of_a_figure_with_marks_where_it_goes_on() {
        let row = vec![
            ("│ ".to_string(), Md::Rule),
            ("abcdefghij".to_string(), Md::Figure),
        ];
        // 6 cells: 2 for the quote bar, 4 for the figure.
        assert_eq!(text(&[window(&row, 0, 6)]), vec!["│ abc›"]);
        assert_eq!(text(&[window(&row, 3, 6)]), vec!["│ ‹ef›"]);
        assert_eq!(text(&[window(&row, 6, 6)]), vec!["│ ‹hij"]);
        // Only spaces hidden: no mark.
        let short = vec![("ab      ".to_string(), Md::Figure)];
        assert_eq!(text(&[window(&short, 0, 4)]), vec!["ab"]);
        let prose = vec![("some words".to_string(), Md::Text)];
        assert_eq!(window(&prose, 3, 6), prose);
    }

    #[test]
    fn answers_are_marked() {
        let rows = markdown("**Answer (p):** 0.87.", 80);
        assert!(rows[0].iter().all(|(_, m)| *m == Md::Answer), "{rows:?}");
    }
}
