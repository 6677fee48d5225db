//! A 3 × 5 pixel font for the labels of `bench sweep --plot` (digits, a few capitals and
//! signs): enough to number the axes without shipping a font file.

/// The rows of a glyph, top first, three bits each (4 = left column).
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_uppercase() {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '-' => [0, 0, 7, 0, 0],
        '.' => [0, 0, 0, 0, 2],
        '/' => [1, 1, 2, 4, 4],
        ':' => [0, 2, 0, 2, 0],
        'A' => [2, 5, 7, 5, 5],
        'C' => [3, 4, 4, 4, 3],
        'D' => [6, 5, 5, 5, 6],
        'E' => [7, 4, 7, 4, 7],
        'G' => [3, 4, 5, 5, 3],
        'H' => [5, 5, 7, 5, 5],
        'I' => [7, 2, 2, 2, 7],
        'L' => [4, 4, 4, 4, 7],
        'M' => [5, 7, 7, 5, 5],
        'N' => [6, 5, 5, 5, 5],
        'O' => [2, 5, 5, 5, 2],
        'P' => [6, 5, 6, 4, 4],
        'R' => [6, 5, 6, 5, 5],
        'S' => [3, 4, 2, 1, 6],
        'T' => [7, 2, 2, 2, 2],
        'U' => [5, 5, 5, 5, 7],
        'Y' => [5, 5, 2, 2, 2],
        _ => [0; 5],
    }
}

/// The pixels (x, y) lit by `text` drawn from its top-left corner at `scale` pixels per dot.
pub fn pixels(text: &str, x: f64, y: f64, scale: f64) -> Vec<(f64, f64)> {
    let mut out = vec![];
    for (i, c) in text.chars().enumerate() {
        let left = x + i as f64 * 4.0 * scale;
        for (row, bits) in glyph(c).iter().enumerate() {
            for col in 0..3 {
                if bits & (4 >> col) != 0 {
                    for dy in 0..scale as i32 {
                        for dx in 0..scale as i32 {
                            out.push((
                                left + col as f64 * scale + dx as f64,
                                y + row as f64 * scale + dy as f64,
                            ));
                        }
                    }
                }
            }
        }
    }
    out
}

/// Width in pixels of `text` at `scale`.
pub fn width(text: &str, scale: f64) -> f64 {
    (text.chars().count() as f64 * 4.0 - 1.0) * scale
}

/// A decade 10^d as a label: "0.01", "1", "100", or "1E-5" beyond three places.
pub fn decade(d: i32) -> String {
    match d {
        0..=3 => format!("1{}", "0".repeat(d as usize)),
        -3..=-1 => format!("0.{}1", "0".repeat((-d - 1) as usize)),
        _ => format!("1E{d}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_read_as_numbers() {
        assert_eq!(decade(0), "1");
        assert_eq!(decade(2), "100");
        assert_eq!(decade(-2), "0.01");
        assert_eq!(decade(-5), "1E-5");
        for d in -3..=3 {
            assert!((decade(d).parse::<f64>().unwrap() - 10f64.powi(d)).abs() < 1e-12);
        }
    }

    #[test]
    fn a_one_is_drawn_with_its_foot() {
        // "1": 1 + 2 + 1 + 1 + 3 dots.
        assert_eq!(pixels("1", 0.0, 0.0, 1.0).len(), 8);
        assert_eq!(width("10", 2.0), 14.0);
    }
}
