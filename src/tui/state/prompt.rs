//! A line being typed on the message line: the pixel to go to, or an answer to an exercise.

use crate::tui::msg::Msg;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Prompt {
    /// `g`: image coordinates "x,y".
    Goto(String),
    /// `a` then Enter: an answer to an exercise.
    Answer { exercise: usize, text: String },
}

impl Prompt {
    /// Typing: a character (the line holds 200 at most) or Backspace.
    pub fn edit(&mut self, msg: &Msg) {
        let (Prompt::Goto(s) | Prompt::Answer { text: s, .. }) = self;
        match *msg {
            Msg::Input(c) if s.chars().count() < 200 => s.push(c),
            Msg::Backspace => {
                s.pop();
            }
            _ => {}
        }
    }
}

/// "x,y" or "x y".
pub fn parse_pixel(s: &str) -> Option<(u32, u32)> {
    let parts: Vec<&str> = s
        .split([',', ' '])
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .collect();
    match parts.as_slice() {
        [x, y] => Some((x.parse().ok()?, y.parse().ok()?)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_are_two_whole_numbers() {
        assert_eq!(parse_pixel("3,4"), Some((3, 4)));
        assert_eq!(parse_pixel(" 47 35 "), Some((47, 35)));
        assert_eq!(parse_pixel("48, 2"), Some((48, 2)));
        assert_eq!(parse_pixel("1"), None);
        assert_eq!(parse_pixel("1,2,3"), None);
        assert_eq!(parse_pixel("-1,2"), None);
    }

    #[test]
    fn typing_stops_at_200_characters() {
        let mut p = Prompt::Goto(String::new());
        for _ in 0..250 {
            p.edit(&Msg::Input('1'));
        }
        p.edit(&Msg::Backspace);
        assert_eq!(p, Prompt::Goto("1".repeat(199)));
    }
}
