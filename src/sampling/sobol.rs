//! The sample points of the path tracer: well-spread random numbers. Independent random
//! numbers clump and leave gaps, and with a few samples per pixel the clumps are noise; here
//! the N samples of a pixel spread evenly over every pair of numbers a path draws.
//!
//! Each pair is the first two dimensions of Sobol's sequence, a (0, 2)-sequence: any 2^m
//! consecutive points from an index divisible by 2^m put exactly one point in every rectangle
//! [a/2^j, (a+1)/2^j) × [b/2^k, (b+1)/2^k) with j + k = m (an elementary interval of area
//! 1/2^m). Owen's scrambling (Burley 2020, "Practical Hash-based Owen Scrambling") randomizes
//! the points without breaking that, so each is uniform on [0, 1)² and the estimates stay
//! unbiased; and each pair takes its own scramble and its own shuffle of the sample order
//! ("padding"), so that two pairs are independent of each other.

/// A number for pixel (x, y) and a seed, different for every pixel (SplitMix64 mixes the three).
pub fn pixel_key(seed: u64, x: u32, y: u32) -> u64 {
    mix(seed ^ ((x as u64) << 32 | y as u64).wrapping_mul(GOLDEN))
}

/// 2⁶⁴ divided by the golden ratio, odd: multiplying by it spreads consecutive numbers apart.
const GOLDEN: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's finaliser: every input bit changes about half the output bits.
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Sample number `index` of the pixel whose key is `key`: a point with as many dimensions as a
/// path needs, read two at a time (`pair`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SamplePoint {
    /// The pixel's key (`pixel_key`): the scrambles and shuffles of its pairs.
    pub key: u64,
    /// Which of the pixel's samples this is: 0, 1, 2, …
    pub index: u32,
}

impl SamplePoint {
    /// Sample `index` of the pixel whose key is `key`.
    pub fn new(key: u64, index: u32) -> SamplePoint {
        SamplePoint { key, index }
    }

    /// Dimension pair `dim` of the point, in [0, 1)².
    pub fn pair(&self, dim: u32) -> [f64; 2] {
        let seeds = mix(self.key ^ (dim as u64 + 1).wrapping_mul(GOLDEN));
        let (shuffle, sx) = (seeds as u32, (seeds >> 32) as u32);
        let sy = (seeds.wrapping_mul(GOLDEN) >> 32) as u32;
        // The shuffled index, `owen_scramble(index, shuffle)` before its last mirror.
        let shuffled = laine_karras(self.index.reverse_bits(), shuffle);
        // Owen's scramble of each coordinate, on the mirrored fractions `mirrored_sobol_pair`
        // gives (see `owen_scramble`).
        let [x, y] = mirrored_sobol_pair_of_mirrored(shuffled);
        // Both mirrored back at once: mirroring 64 bits mirrors each half and swaps them.
        let both = ((laine_karras(y, sy) as u64) << 32 | laine_karras(x, sx) as u64).reverse_bits();
        [unit((both >> 32) as u32), unit(both as u32)]
    }
}

/// Point `i` of Sobol's sequence in its first two dimensions, as 32-bit binary fractions
/// (bit 31 is the ½ digit). The first dimension is van der Corput's: i's bits mirrored about
/// the binary point. The second multiplies i's bits by the generator matrix whose columns are
/// v₁ = ½, v_k = v_{k−1} xor v_{k−1}/2 (Pascal's triangle mod 2).
pub fn sobol_pair(i: u32) -> [u32; 2] {
    mirrored_sobol_pair(i).map(u32::reverse_bits)
}

/// `sobol_pair(i)` with each fraction's bits mirrored (bit 0 is the ½ digit): the first is i
/// itself, the second the xor of the mirrored columns of i's set bits, a byte at a time.
fn mirrored_sobol_pair(i: u32) -> [u32; 2] {
    [i, xor_by_byte(i, &SECOND_BY_BYTE)]
}

/// `mirrored_sobol_pair(j.reverse_bits())`. The second coordinate is linear in the index's
/// bits (xor), so it is read off j's bytes directly, each bit standing for the column of its
/// mirror image: the second coordinate need not wait for the index to be mirrored back.
fn mirrored_sobol_pair_of_mirrored(j: u32) -> [u32; 2] {
    [j.reverse_bits(), xor_by_byte(j, &SECOND_BY_MIRRORED_BYTE)]
}

/// The xor of each byte's entry in its table: a GF(2)-linear function of the bits, a byte at
/// a time.
#[inline(always)]
fn xor_by_byte(bits: u32, tables: &[[u32; 256]; 4]) -> u32 {
    bits.to_le_bytes()
        .iter()
        .zip(tables)
        .fold(0, |y, (&byte, table)| y ^ table[byte as usize])
}

/// For each byte of an index, the mirrored second-dimension value of each of its 256 values.
const SECOND_BY_BYTE: [[u32; 256]; 4] = second_by_byte(false);

/// The same for each byte of a mirrored index: bit p of it is bit 31 − p of the index.
const SECOND_BY_MIRRORED_BYTE: [[u32; 256]; 4] = second_by_byte(true);

const fn second_by_byte(mirrored: bool) -> [[u32; 256]; 4] {
    // The columns mirrored: c₁ = 1 (the ½ digit), c_k = c_{k−1} xor 2·c_{k−1}.
    let mut columns = [0u32; 32];
    let (mut c, mut k) = (1u32, 0);
    while k < 32 {
        columns[k] = c;
        c ^= c << 1;
        k += 1;
    }
    let mut tables = [[0u32; 256]; 4];
    let mut byte = 0;
    while byte < 4 {
        let mut value = 0;
        while value < 256 {
            let (mut y, mut bit) = (0u32, 0);
            while bit < 8 {
                if (value >> bit) & 1 == 1 {
                    let place = byte * 8 + bit;
                    y ^= columns[if mirrored { 31 - place } else { place }];
                }
                bit += 1;
            }
            tables[byte][value] = y;
            value += 1;
        }
        byte += 1;
    }
    tables
}

/// Owen's nested uniform scramble of a binary fraction: each digit flipped or not at random,
/// the coin depending on the digits before it (Burley 2020: mirror the bits, so that the digits
/// before come below; Laine and Karras's hash, in which a bit changes only bits above it; mirror
/// back). Applied to an index it shuffles the sample order, each aligned block of 2^m indices
/// onto an aligned block.
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    laine_karras(x.reverse_bits(), seed).reverse_bits()
}

/// Laine and Karras's permutation as Burley gives it: additions and multiplications by even
/// numbers, so that every bit of the result depends only on the bits at and below it.
fn laine_karras(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// A 32-bit binary fraction as a number in [0, 1).
fn unit(x: u32) -> f64 {
    x as f64 * (1.0 / 4_294_967_296.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::chi_square_uniform;

    /// The first points of the sequence, worked by hand: van der Corput's 0, ½, ¼, ¾, ⅛ and
    /// the second dimension's 0, ½, ¾, ¼, ⅝ (i = 2 = 10₂ takes v₂ = ¾; i = 3 = 11₂ takes
    /// v₁ xor v₂ = 0.1₂ xor 0.11₂ = 0.01₂ = ¼; i = 4 takes v₃ = 0.101₂ = ⅝).
    #[test]
    fn the_first_sobol_points_are_those_worked_by_hand() {
        let points: Vec<[f64; 2]> = (0..5).map(|i| sobol_pair(i).map(unit)).collect();
        assert_eq!(
            points,
            [
                [0.0, 0.0],
                [0.5, 0.5],
                [0.25, 0.75],
                [0.75, 0.25],
                [0.125, 0.625]
            ]
        );
    }

    /// Counts of `points` in each elementary interval of 2^j × 2^k cells, j + k = m.
    fn one_in_each_elementary_interval(points: &[[f64; 2]], m: u32) -> bool {
        (0..=m).all(|j| {
            let (cols, rows) = (1usize << j, 1usize << (m - j));
            let mut counts = vec![0; cols * rows];
            for [x, y] in points {
                counts[(x * cols as f64) as usize * rows + (y * rows as f64) as usize] += 1;
            }
            counts.iter().all(|&c| c == 1)
        })
    }

    /// The (0, m, 2)-net property, the reason for the sequence: a pixel's first 2^m samples
    /// put one point in every elementary interval of area 2^−m, in every pair, scrambled,
    /// shuffled, for any pixel.
    #[test]
    fn a_pixels_first_power_of_two_samples_form_a_net_in_every_pair() {
        for m in 0..=8 {
            for (seed, dim) in [(0, 0), (1, 3), (0xDEAD_BEEF, 17), (u64::MAX, 1000)] {
                let key = pixel_key(seed, 5, 9);
                let points: Vec<[f64; 2]> = (0..1u32 << m)
                    .map(|i| SamplePoint::new(key, i).pair(dim))
                    .collect();
                assert!(
                    one_in_each_elementary_interval(&points, m),
                    "2^{m} samples, seed {seed}, pair {dim}: {points:?}"
                );
            }
        }
    }

    /// Without the scramble the points would be the sequence's own; with it, one point taken
    /// over many pixels is uniform on the square (χ² on 16 × 16 cells).
    #[test]
    fn a_scrambled_point_is_uniform_over_pixels() {
        for (index, dim) in [(0, 0), (1, 0), (5, 2)] {
            let mut counts = vec![0.0; 256];
            for x in 0..25_600 {
                let [u, v] = SamplePoint::new(pixel_key(7, x, 3), index).pair(dim);
                counts[(u * 16.0) as usize * 16 + (v * 16.0) as usize] += 1.0;
            }
            let chi2 = chi_square_uniform(&counts);
            // 255 degrees of freedom: the 99.9 % point is about 330.
            assert!(chi2 < 330.0, "sample {index}, pair {dim}: χ² = {chi2}");
        }
    }

    /// Padding: two pairs of the same sample are independent, within a pixel. Were the pairs
    /// not shuffled apart, sample i would take Sobol point i in both, and the second
    /// coordinate's first digit, the parity of i, flipped by one coin per pair, would put
    /// pair 0 and pair 1 in the same half for all 16 samples of a pixel or for none. Shuffled,
    /// about half the samples agree, and hardly a pixel is all or nothing.
    #[test]
    fn two_pairs_of_a_sample_are_independent() {
        let pixels = 400;
        let (mut agree, mut all_or_none) = (0, 0);
        for x in 0..pixels {
            let key = pixel_key(11, x, 0);
            let same = (0..16)
                .filter(|&i| {
                    let p = SamplePoint::new(key, i);
                    (p.pair(0)[1] < 0.5) == (p.pair(1)[1] < 0.5)
                })
                .count();
            agree += same;
            all_or_none += usize::from(same == 0 || same == 16);
        }
        let mean = agree as f64 / pixels as f64;
        assert!((mean - 8.0).abs() < 0.5, "mean agreement {mean} of 16");
        assert!(
            all_or_none * 20 < pixels as usize,
            "{all_or_none} of {pixels} pixels"
        );
        // And over many pixels the first coordinates of the two pairs fill a 16 × 16 grid
        // evenly.
        let mut counts = vec![0.0; 256];
        for x in 0..1_600 {
            let key = pixel_key(11, x, 0);
            for i in 0..16 {
                let p = SamplePoint::new(key, i);
                let (a, b) = (p.pair(0)[0], p.pair(1)[0]);
                counts[(a * 16.0) as usize * 16 + (b * 16.0) as usize] += 1.0;
            }
        }
        let chi2 = chi_square_uniform(&counts);
        assert!(chi2 < 330.0, "χ² = {chi2}");
    }

    /// `pair`'s two shortcuts (the second coordinate read off the shuffled index while it is
    /// still mirrored, and both coordinates mirrored back as one 64-bit word) give the points
    /// of the plain steps: `owen_scramble`, `mirrored_sobol_pair`, each fraction mirrored on
    /// its own.
    #[test]
    fn pair_is_the_plain_steps() {
        let mut rng = crate::sampling::Rng::for_pixel(8, 9, 10);
        let mut draw = |n: f64| (rng.uniform() * n) as u64;
        let named = [
            (0, 0, 0),
            (1, 2, 3),
            (u64::MAX, 31, 1 << 20),
            (0x5EED, 7, 12345),
        ];
        let drawn = (0..2_000).map(|_| (draw(1e18), draw(40.0) as u32, draw(4e9) as u32));
        for (k, dim, index) in named.into_iter().chain(drawn.collect::<Vec<_>>()) {
            let point = SamplePoint::new(pixel_key(k, 3, 4), index);
            let seeds = mix(point.key ^ (dim as u64 + 1).wrapping_mul(GOLDEN));
            let (shuffle, sx) = (seeds as u32, (seeds >> 32) as u32);
            let sy = (seeds.wrapping_mul(GOLDEN) >> 32) as u32;
            let [x, y] = mirrored_sobol_pair(owen_scramble(index, shuffle));
            let each = [laine_karras(x, sx), laine_karras(y, sy)].map(|m| unit(m.reverse_bits()));
            assert_eq!(point.pair(dim), each, "key {k}, pair {dim}, sample {index}");
        }
    }

    /// Reading the second coordinate off a mirrored index gives what reading it off the index
    /// gives.
    #[test]
    fn the_second_coordinate_reads_alike_off_a_mirrored_index() {
        let mut rng = crate::sampling::Rng::for_pixel(5, 6, 7);
        let indices = [0, 1, 2, 0x8000_0000, u32::MAX, 0x1234_5678]
            .into_iter()
            .chain((0..10_000).map(|_| (rng.uniform() * 4_294_967_296.0) as u32));
        for i in indices {
            assert_eq!(
                mirrored_sobol_pair_of_mirrored(i.reverse_bits()),
                mirrored_sobol_pair(i),
                "index {i}"
            );
        }
    }

    /// Owen's scramble is a permutation of the fractions that keeps a fraction's first k
    /// digits a function of the first k digits alone (checked on 3 digits: the 8 intervals of
    /// width ⅛ go onto the 8 intervals).
    #[test]
    fn the_scramble_permutes_intervals_onto_intervals() {
        for seed in [0, 1, 0x1234_5678, u32::MAX] {
            let top = |x: u32| x >> 29;
            let image: Vec<u32> = (0..8u32)
                .map(|d| {
                    let outs: Vec<u32> = (0..64u32)
                        .map(|low| top(owen_scramble((d << 29) | (low * 0x0076_5431), seed)))
                        .collect();
                    assert!(outs.iter().all(|&o| o == outs[0]), "seed {seed}: {outs:?}");
                    outs[0]
                })
                .collect();
            let mut sorted = image.clone();
            sorted.sort();
            assert_eq!(sorted, (0..8).collect::<Vec<_>>(), "seed {seed}: {image:?}");
        }
    }
}
