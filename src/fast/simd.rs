//! Four f64 lanes, in whichever instructions the processor running raytree has.
//!
//! The wing's lane code is written once, over the trait `F64x4`, and compiled three times:
//! with `wide::f64x4` for any x86-64 (two SSE2 halves) and other processors, and with `Avx`
//! (one 256-bit AVX register) for processors of the x86-64-v3 level (AVX2 and FMA: Intel
//! since 2013, AMD since 2015) and of the x86-64-v4 level (AVX-512 as well: the same four
//! lanes, with 32 registers and mask registers to hold them). `level()` asks the processor
//! once; the wing's entry points (`with_lanes`) pick their copy by it. Every type gives every
//! lane the same bits: the same IEEE operations, and comparisons, minimum and maximum with
//! `wide`'s rules for NaN.
//!
//! The rest of raytree is compiled for any x86-64. A build for x86-64-v3 or later
//! (`-C target-cpu=...`) makes `wide::f64x4` one AVX register too; the copies are then alike.

use std::fmt::Debug;
use std::ops::{Add, BitAnd, BitOr, BitOrAssign, BitXor, Div, Mul, Neg, Not, Sub};

/// Four f64 lanes and the operations the wing's lane code uses. A comparison gives a mask:
/// all ones in the lanes where it holds, zero elsewhere.
pub trait F64x4:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitOrAssign
    + BitXor<Output = Self>
    + Not<Output = Self>
{
    /// 0.0 in every lane.
    const ZERO: Self;
    /// 1.0 in every lane.
    const ONE: Self;
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// Lanes 0 to 3.
    fn new(lanes: [f64; 4]) -> Self;
    /// Lanes 0 to 3 from four numbers in registers: `new` goes through memory, where one
    /// wide load of four narrow stores stalls on store forwarding.
    fn setr(a: f64, b: f64, c: f64, d: f64) -> Self;
    /// The lanes as an array.
    fn to_array(self) -> [f64; 4];
    /// A mask: `if_one` where it is all ones, `if_zero` where it is zero.
    fn bitselect(self, if_one: Self, if_zero: Self) -> Self;
    /// Bit i set when lane i's sign bit is (for a mask: when lane i is on).
    fn to_bitmask(self) -> u32;
    /// Some lane's sign bit is set.
    fn any(self) -> bool {
        self.to_bitmask() != 0
    }
    /// Every lane's sign bit is set.
    fn all(self) -> bool {
        self.to_bitmask() == 0b1111
    }
    /// ==, false where either lane is NaN.
    fn simd_eq(self, rhs: Self) -> Self;
    /// !=, true where either lane is NaN.
    fn simd_ne(self, rhs: Self) -> Self;
    /// <, false where either lane is NaN.
    fn simd_lt(self, rhs: Self) -> Self;
    /// >, false where either lane is NaN.
    fn simd_gt(self, rhs: Self) -> Self;
    /// <=, false where either lane is NaN.
    fn simd_le(self, rhs: Self) -> Self;
    /// >=, false where either lane is NaN.
    fn simd_ge(self, rhs: Self) -> Self;
    /// All ones where the lane is NaN.
    fn is_nan(self) -> Self;
    /// All ones where the lane is neither infinite nor NaN.
    fn is_finite(self) -> Self;
    /// All ones where the lane's sign bit is set (−0.0 included).
    fn is_sign_negative(self) -> Self;
    /// |x|.
    fn abs(self) -> Self;
    /// √x, correctly rounded.
    fn sqrt(self) -> Self;
    /// ⌊x⌋, bit for bit `f64::floor`.
    fn floor(self) -> Self;
    /// 1/x, correctly rounded (a division).
    fn recip(self) -> Self {
        Self::ONE / self
    }
    /// The smaller; `self` where `rhs` is NaN.
    fn min(self, rhs: Self) -> Self;
    /// The larger; `self` where `rhs` is NaN.
    fn max(self, rhs: Self) -> Self;
    /// The processor's minimum: `rhs` where either is NaN (or both are zeros).
    fn fast_min(self, rhs: Self) -> Self;
    /// The processor's maximum: `rhs` where either is NaN (or both are zeros).
    fn fast_max(self, rhs: Self) -> Self;

    /// `f()` run as a function of its own, not inlined into its caller, and compiled for the
    /// instructions of these lanes. Give it an `#[inline(always)]` closure: its body is then
    /// compiled there, with everything it inlines.
    fn outlined<R>(f: impl FnOnce() -> R) -> R;
}

/// `$body`, an expression using the lane type `$v`, compiled for each instruction set and
/// run in the copy for this processor's `level()`. The wing's entry points are written so:
/// everything `$body` calls with `$v` is `#[inline(always)]` (or `F64x4::outlined`), so that
/// it is compiled inside the copy, with the copy's instructions. Without a lane type
/// (`with_lanes!(=> body)`), scalar code compiled for the processor: the functions the
/// compiler inlines into it, and its copies of structs, use the wider instructions too.
macro_rules! with_lanes {
    (=> $body:expr) => {
        $crate::fast::simd::with_lanes!(_Lanes => $body)
    };
    ($v:ident => $body:expr) => {
        match $crate::fast::simd::level() {
            #[cfg(target_arch = "x86_64")]
            $crate::fast::simd::Level::V4 => $crate::fast::simd::with_lanes!(@copy V4, $v => $body),
            #[cfg(target_arch = "x86_64")]
            $crate::fast::simd::Level::V3 => $crate::fast::simd::with_lanes!(@copy V3, $v => $body),
            _ => {
                type $v = $crate::fast::simd::Wide;
                $body
            }
        }
    };
    // The copy for the instruction set `$isa`, `$body` inlined into it.
    (@copy $isa:ident, $v:ident => $body:expr) => {{
        type $v = $crate::fast::simd::Avx<$crate::fast::simd::$isa>;
        <$v as $crate::fast::simd::F64x4>::outlined(
            #[inline(always)]
            || $body,
        )
    }};
}
pub(crate) use with_lanes;

/// `wide`'s four lanes: one AVX register when raytree is compiled for AVX, two SSE2 halves
/// otherwise (or the processor's own vectors elsewhere).
pub type Wide = wide::f64x4;

impl F64x4 for Wide {
    const ZERO: Self = wide::f64x4::ZERO;
    const ONE: Self = wide::f64x4::ONE;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        wide::f64x4::splat(x)
    }
    #[inline(always)]
    fn new(lanes: [f64; 4]) -> Self {
        wide::f64x4::new(lanes)
    }
    #[inline(always)]
    fn setr(a: f64, b: f64, c: f64, d: f64) -> Self {
        #[cfg(all(target_arch = "x86_64", target_feature = "avx"))]
        {
            // SAFETY: compiled for AVX, where an f64x4 is one __m256d (the transmute checks
            // the sizes).
            unsafe { std::mem::transmute::<Avx, Wide>(Avx::setr(a, b, c, d)) }
        }
        #[cfg(not(all(target_arch = "x86_64", target_feature = "avx")))]
        {
            wide::f64x4::new([a, b, c, d])
        }
    }
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        wide::f64x4::to_array(self)
    }
    #[inline(always)]
    fn bitselect(self, if_one: Self, if_zero: Self) -> Self {
        wide::f64x4::bitselect(self, if_one, if_zero)
    }
    #[inline(always)]
    fn to_bitmask(self) -> u32 {
        wide::f64x4::to_bitmask(self)
    }
    #[inline(always)]
    fn simd_eq(self, rhs: Self) -> Self {
        wide::f64x4::simd_eq(self, rhs)
    }
    #[inline(always)]
    fn simd_ne(self, rhs: Self) -> Self {
        wide::f64x4::simd_ne(self, rhs)
    }
    #[inline(always)]
    fn simd_lt(self, rhs: Self) -> Self {
        wide::f64x4::simd_lt(self, rhs)
    }
    #[inline(always)]
    fn simd_gt(self, rhs: Self) -> Self {
        wide::f64x4::simd_gt(self, rhs)
    }
    #[inline(always)]
    fn simd_le(self, rhs: Self) -> Self {
        wide::f64x4::simd_le(self, rhs)
    }
    #[inline(always)]
    fn simd_ge(self, rhs: Self) -> Self {
        wide::f64x4::simd_ge(self, rhs)
    }
    #[inline(always)]
    fn is_nan(self) -> Self {
        wide::f64x4::is_nan(self)
    }
    #[inline(always)]
    fn is_finite(self) -> Self {
        wide::f64x4::is_finite(self)
    }
    #[inline(always)]
    fn is_sign_negative(self) -> Self {
        wide::f64x4::is_sign_negative(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        wide::f64x4::abs(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        wide::f64x4::sqrt(self)
    }
    #[inline(always)]
    fn floor(self) -> Self {
        wide::f64x4::new(self.to_array().map(crate::geometry::floor::floor))
    }
    #[inline(always)]
    fn min(self, rhs: Self) -> Self {
        wide::f64x4::min(self, rhs)
    }
    #[inline(always)]
    fn max(self, rhs: Self) -> Self {
        wide::f64x4::max(self, rhs)
    }
    #[inline(always)]
    fn fast_min(self, rhs: Self) -> Self {
        wide::f64x4::fast_min(self, rhs)
    }
    #[inline(always)]
    fn fast_max(self, rhs: Self) -> Self {
        wide::f64x4::fast_max(self, rhs)
    }
    #[inline(always)]
    fn outlined<R>(f: impl FnOnce() -> R) -> R {
        #[inline(never)]
        fn run<R>(f: impl FnOnce() -> R) -> R {
            f()
        }
        run(f)
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
use avx::Isa;
#[cfg(target_arch = "x86_64")]
pub(crate) use avx::{Avx, V3, V4};

#[cfg(target_arch = "x86_64")]
mod avx {
    use std::arch::x86_64::*;
    use std::fmt::Debug;
    use std::marker::PhantomData;
    use std::ops::{Add, BitAnd, BitOr, BitOrAssign, BitXor, Div, Mul, Neg, Not, Sub};

    use super::F64x4;

    /// Four lanes in one AVX register, in code compiled for the instruction set `I`
    /// (x86-64-v3, or x86-64-v4 with AVX-512's 32 registers and mask registers: the same
    /// instructions on four lanes, fewer of them spilled).
    ///
    /// Only code that runs where `level()` is `I`'s level or higher touches one: the wing's
    /// entry points create them inside their copies for `I` (`with_lanes`), where every method
    /// below is inlined and becomes one or two AVX instructions. That is the safety argument
    /// of each `unsafe` block here: the processor has AVX and AVX2.
    #[derive(Clone, Copy, Debug)]
    #[repr(transparent)]
    pub struct Avx<I = V3>(__m256d, PhantomData<I>);

    /// An instruction set the wing has a copy for, and how code is compiled for it.
    pub trait Isa: Copy + Debug {
        /// `f()` compiled for this instruction set, out of line (`F64x4::outlined`).
        fn outlined<R>(f: impl FnOnce() -> R) -> R;
    }

    /// x86-64-v3: AVX, AVX2, FMA, BMI1, BMI2, LZCNT, MOVBE.
    #[derive(Clone, Copy, Debug)]
    pub struct V3;

    /// x86-64-v4: x86-64-v3 and AVX-512 (F, VL, DQ, BW, CD).
    #[derive(Clone, Copy, Debug)]
    pub struct V4;

    // rustc drops `#[inline(never)]` from a function with `#[target_feature]`, and LLVM would
    // then inline a copy into another that calls it (the CSG pieces into a search, whose loop
    // then spills its registers). `run` keeps the attribute and `copy` stays behind it: a
    // build for any x86-64 cannot inline `copy` into `run`, and in a build for the level
    // itself `run` becomes the copy.
    macro_rules! isa {
        ($level:ty, $features:literal) => {
            impl Isa for $level {
                #[inline(always)]
                fn outlined<R>(f: impl FnOnce() -> R) -> R {
                    #[target_feature(enable = $features)]
                    fn copy<R>(f: impl FnOnce() -> R) -> R {
                        f()
                    }
                    #[inline(never)]
                    fn run<R>(f: impl FnOnce() -> R) -> R {
                        // SAFETY: see `Avx`'s comment: the processor has these features.
                        unsafe { copy(f) }
                    }
                    run(f)
                }
            }
        };
    }

    // The features `processor_is_v3` and `processor_is_v4` check.
    isa!(V3, "avx,avx2,fma,bmi1,bmi2,lzcnt,movbe,popcnt");
    isa!(
        V4,
        "avx,avx2,fma,bmi1,bmi2,lzcnt,movbe,popcnt,avx512f,avx512vl,avx512dq,avx512bw,avx512cd"
    );

    /// All 64 bits of a lane set.
    const ONES: u64 = u64::MAX;

    impl<I: Isa> Avx<I> {
        /// The lanes as they sit in memory (a transmute: no instruction at all).
        #[inline(always)]
        const fn from_array(lanes: [f64; 4]) -> Avx<I> {
            // SAFETY: __m256d is four f64 (the transmute checks the sizes).
            Avx::wrap(unsafe { std::mem::transmute::<[f64; 4], __m256d>(lanes) })
        }

        #[inline(always)]
        const fn wrap(v: __m256d) -> Avx<I> {
            Avx(v, PhantomData)
        }

        #[inline(always)]
        fn cmp<const IMM: i32>(self, rhs: Avx<I>) -> Avx<I> {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_cmp_pd::<IMM>(self.0, rhs.0) })
        }
    }

    macro_rules! binary {
        ($trait:ident, $method:ident, $intrinsic:ident) => {
            impl<I: Isa> $trait for Avx<I> {
                type Output = Avx<I>;
                #[inline(always)]
                fn $method(self, rhs: Avx<I>) -> Avx<I> {
                    // SAFETY: see the type's comment.
                    Avx::wrap(unsafe { $intrinsic(self.0, rhs.0) })
                }
            }
        };
    }

    binary!(Add, add, _mm256_add_pd);
    binary!(Sub, sub, _mm256_sub_pd);
    binary!(Mul, mul, _mm256_mul_pd);
    binary!(Div, div, _mm256_div_pd);
    binary!(BitAnd, bitand, _mm256_and_pd);
    binary!(BitOr, bitor, _mm256_or_pd);
    binary!(BitXor, bitxor, _mm256_xor_pd);

    impl<I: Isa> BitOrAssign for Avx<I> {
        #[inline(always)]
        fn bitor_assign(&mut self, rhs: Avx<I>) {
            *self = *self | rhs;
        }
    }

    impl<I: Isa> Neg for Avx<I> {
        type Output = Avx<I>;
        /// The sign bit flipped, as `wide` negates.
        #[inline(always)]
        fn neg(self) -> Avx<I> {
            self ^ Avx::splat(-0.0)
        }
    }

    impl<I: Isa> Not for Avx<I> {
        type Output = Avx<I>;
        #[inline(always)]
        fn not(self) -> Avx<I> {
            self ^ Avx::splat(f64::from_bits(ONES))
        }
    }

    impl<I: Isa> F64x4 for Avx<I> {
        const ZERO: Self = Avx::from_array([0.0; 4]);
        const ONE: Self = Avx::from_array([1.0; 4]);

        #[inline(always)]
        fn splat(x: f64) -> Self {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_set1_pd(x) })
        }
        #[inline(always)]
        fn new(lanes: [f64; 4]) -> Self {
            Avx::from_array(lanes)
        }
        #[inline(always)]
        fn setr(a: f64, b: f64, c: f64, d: f64) -> Self {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_setr_pd(a, b, c, d) })
        }
        #[inline(always)]
        fn to_array(self) -> [f64; 4] {
            // SAFETY: __m256d is four f64 (the transmute checks the sizes).
            unsafe { std::mem::transmute::<__m256d, [f64; 4]>(self.0) }
        }
        #[inline(always)]
        fn bitselect(self, if_one: Self, if_zero: Self) -> Self {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe {
                _mm256_or_pd(
                    _mm256_and_pd(if_one.0, self.0),
                    _mm256_andnot_pd(self.0, if_zero.0),
                )
            })
        }
        #[inline(always)]
        fn to_bitmask(self) -> u32 {
            // SAFETY: see the type's comment.
            unsafe { _mm256_movemask_pd(self.0) as u32 }
        }
        #[inline(always)]
        fn simd_eq(self, rhs: Self) -> Self {
            self.cmp::<_CMP_EQ_OQ>(rhs)
        }
        #[inline(always)]
        fn simd_ne(self, rhs: Self) -> Self {
            self.cmp::<_CMP_NEQ_UQ>(rhs)
        }
        #[inline(always)]
        fn simd_lt(self, rhs: Self) -> Self {
            self.cmp::<_CMP_LT_OQ>(rhs)
        }
        #[inline(always)]
        fn simd_gt(self, rhs: Self) -> Self {
            self.cmp::<_CMP_GT_OQ>(rhs)
        }
        #[inline(always)]
        fn simd_le(self, rhs: Self) -> Self {
            self.cmp::<_CMP_LE_OQ>(rhs)
        }
        #[inline(always)]
        fn simd_ge(self, rhs: Self) -> Self {
            self.cmp::<_CMP_GE_OQ>(rhs)
        }
        #[inline(always)]
        fn is_nan(self) -> Self {
            self.cmp::<_CMP_UNORD_Q>(self)
        }
        #[inline(always)]
        fn is_finite(self) -> Self {
            // |x| < ∞ fails for ∞ and for NaN (an ordered comparison).
            self.abs().simd_lt(Avx::splat(f64::INFINITY))
        }
        #[inline(always)]
        fn is_sign_negative(self) -> Self {
            // SAFETY: see the type's comment. A lane read as a signed integer is negative
            // exactly when its sign bit is set.
            Avx::wrap(unsafe {
                let bits = _mm256_castpd_si256(self.0);
                _mm256_castsi256_pd(_mm256_cmpgt_epi64(_mm256_setzero_si256(), bits))
            })
        }
        #[inline(always)]
        fn abs(self) -> Self {
            self & Avx::splat(f64::from_bits(ONES >> 1))
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_sqrt_pd(self.0) })
        }
        #[inline(always)]
        fn floor(self) -> Self {
            // SAFETY: see the type's comment. Rounding toward −∞ keeps −0, ±∞ and NaN.
            Avx::wrap(unsafe {
                _mm256_round_pd::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(self.0)
            })
        }
        #[inline(always)]
        fn min(self, rhs: Self) -> Self {
            // MINPD gives its second operand where either is NaN: `self` must win there.
            rhs.is_nan().blend(self, self.fast_min(rhs))
        }
        #[inline(always)]
        fn max(self, rhs: Self) -> Self {
            rhs.is_nan().blend(self, self.fast_max(rhs))
        }
        #[inline(always)]
        fn fast_min(self, rhs: Self) -> Self {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_min_pd(self.0, rhs.0) })
        }
        #[inline(always)]
        fn fast_max(self, rhs: Self) -> Self {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_max_pd(self.0, rhs.0) })
        }
        #[inline(always)]
        fn outlined<R>(f: impl FnOnce() -> R) -> R {
            I::outlined(f)
        }
    }

    impl<I: Isa> Avx<I> {
        /// A mask picks by its lanes' sign bits: `if_set` where set (one BLENDVPD).
        #[inline(always)]
        fn blend(self, if_set: Avx<I>, if_clear: Avx<I>) -> Avx<I> {
            // SAFETY: see the type's comment.
            Avx::wrap(unsafe { _mm256_blendv_pd(if_clear.0, if_set.0, self.0) })
        }
    }
}

/// The instruction sets the wing has copies for, from the oldest.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    /// Any x86-64 (SSE2), or a processor of another architecture.
    Baseline,
    /// x86-64-v3: AVX, AVX2, FMA, BMI1, BMI2, LZCNT, MOVBE.
    V3,
    /// x86-64-v4: x86-64-v3 and AVX-512 (F, VL, DQ, BW, CD). The lanes are still four:
    /// the copy gains AVX-512's 32 registers and its mask registers.
    V4,
}

impl Level {
    /// The name `--stats` prints and `RAYTREE_CPU_LEVEL` takes.
    pub fn name(self) -> &'static str {
        match self {
            Level::Baseline => "x86-64",
            Level::V3 => "x86-64-v3",
            Level::V4 => "x86-64-v4",
        }
    }

    /// The level named `name` (`x86-64`, `x86-64-v3` or `x86-64-v4`).
    pub fn named(name: &str) -> Option<Level> {
        [Level::Baseline, Level::V3, Level::V4]
            .into_iter()
            .find(|level| level.name() == name)
    }
}

/// The copy the wing runs: the one `RAYTREE_CPU_LEVEL` names (`x86-64`, `x86-64-v3` or
/// `x86-64-v4`, to measure or test a copy), if the processor runs it, else the fastest
/// (`preferred_level`). Asked once.
pub fn level() -> Level {
    use std::sync::atomic::{AtomicU8, Ordering};
    // 0: not asked yet, else 1 + the level.
    static LEVEL: AtomicU8 = AtomicU8::new(0);
    match LEVEL.load(Ordering::Relaxed) {
        1 => Level::Baseline,
        2 => Level::V3,
        3 => Level::V4,
        _ => {
            let asked = std::env::var("RAYTREE_CPU_LEVEL")
                .ok()
                .and_then(|name| Level::named(&name));
            let found = match asked {
                Some(asked) => asked.min(level_of_processor()),
                None => preferred_level(),
            };
            LEVEL.store(1 + found as u8, Ordering::Relaxed);
            found
        }
    }
}

/// The fastest copy on this processor: the best it runs, except on an Intel processor with
/// AVX-512, where the x86-64-v4 copy is only the fastest in a build tuned for 256-bit vectors
/// (`-C target-feature=+prefer-256-bit`, which `build.rs` reports as the cfg
/// `raytree_v4_in_256_bits`). Otherwise LLVM copies structs through 512-bit registers in that
/// copy, and on Intel's cores any 512-bit instruction idles a vector port for a while:
/// the CSG peer scene then takes 1.06× the x86-64-v3 copy's time, where the tuned build's
/// x86-64-v4 copy takes 0.92× (docs/performance.md, *Build levels*). AMD's cores run 512-bit
/// instructions as two halves and lose nothing.
pub fn preferred_level() -> Level {
    let best = level_of_processor();
    if best == Level::V4 && !cfg!(raytree_v4_in_256_bits) && processor_is_intel() {
        Level::V3
    } else {
        best
    }
}

/// The best level whose features the processor has.
pub fn level_of_processor() -> Level {
    if processor_is_v4() {
        Level::V4
    } else if processor_is_v3() {
        Level::V3
    } else {
        Level::Baseline
    }
}

/// Whether the processor has every feature the wing's x86-64-v3 copies are compiled with.
fn processor_is_v3() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        has!("avx")
            && has!("avx2")
            && has!("fma")
            && has!("bmi1")
            && has!("bmi2")
            && has!("lzcnt")
            && has!("movbe")
            && has!("popcnt")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether the processor has every feature the wing's x86-64-v4 copies are compiled with.
fn processor_is_v4() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::is_x86_feature_detected as has;
        processor_is_v3()
            && has!("avx512f")
            && has!("avx512vl")
            && has!("avx512dq")
            && has!("avx512bw")
            && has!("avx512cd")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Whether the processor says it is Intel's (CPUID leaf 0: "GenuineIntel").
fn processor_is_intel() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        let id = std::arch::x86_64::__cpuid(0);
        let word = |bytes: &[u8; 4]| u32::from_le_bytes(*bytes);
        (id.ebx, id.edx, id.ecx) == (word(b"Genu"), word(b"ineI"), word(b"ntel"))
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Numbers where lanes' rules differ if they differ at all: both zeros, both infinities,
    /// NaN, the extremes, and ordinary numbers that often repeat (ties).
    fn number() -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(0.0),
            Just(-0.0),
            Just(f64::INFINITY),
            Just(f64::NEG_INFINITY),
            Just(f64::NAN),
            Just(f64::MAX),
            Just(f64::MIN_POSITIVE),
            Just(1.0),
            -4.0..4.0f64,
            any::<f64>(),
        ]
    }

    fn bits<V: F64x4>(v: V) -> [u64; 4] {
        v.to_array().map(f64::to_bits)
    }

    /// Every operation, on `wide`'s lanes and on AVX lanes compiled for `I` (inside `I`'s
    /// copy), to the last bit of every lane.
    fn same<I: Isa>(a: [f64; 4], b: [f64; 4], c: [f64; 4]) -> Result<(), TestCaseError> {
        type Op<V> = fn(V, V, V) -> V;
        fn ops<V: F64x4>() -> Vec<(&'static str, Op<V>)> {
            vec![
                ("add", |a, b, _| a + b),
                ("sub", |a, b, _| a - b),
                ("mul", |a, b, _| a * b),
                ("div", |a, b, _| a / b),
                ("neg", |a, _, _| -a),
                ("and", |a, b, _| a & b),
                ("or", |a, b, _| a | b),
                ("xor", |a, b, _| a ^ b),
                ("not", |a, _, _| !a),
                ("bitselect", |a, b, c| a.simd_lt(b).bitselect(b, c)),
                ("eq", |a, b, _| a.simd_eq(b)),
                ("ne", |a, b, _| a.simd_ne(b)),
                ("lt", |a, b, _| a.simd_lt(b)),
                ("gt", |a, b, _| a.simd_gt(b)),
                ("le", |a, b, _| a.simd_le(b)),
                ("ge", |a, b, _| a.simd_ge(b)),
                ("is_nan", |a, _, _| a.is_nan()),
                ("is_finite", |a, _, _| a.is_finite()),
                ("is_sign_negative", |a, _, _| a.is_sign_negative()),
                ("abs", |a, _, _| a.abs()),
                ("sqrt", |a, _, _| a.sqrt()),
                ("floor", |a, _, _| a.floor()),
                ("recip", |a, _, _| a.recip()),
                ("min", |a, b, _| a.min(b)),
                ("max", |a, b, _| a.max(b)),
                ("fast_min", |a, b, _| a.fast_min(b)),
                ("fast_max", |a, b, _| a.fast_max(b)),
                ("setr", |a, _, _| {
                    let [w, x, y, z] = a.to_array();
                    V::setr(w, x, y, z)
                }),
            ]
        }
        // Each lane type's results: the operations' bits, then the masks' bits, any and all,
        // then ZERO, ONE and a splat.
        type Results = (Vec<[u64; 4]>, Vec<(u32, bool, bool)>, [[u64; 4]; 3]);
        #[inline(always)]
        fn results<V: F64x4>(a: [f64; 4], b: [f64; 4], c: [f64; 4]) -> Results {
            let (va, vb, vc) = (V::new(a), V::new(b), V::new(c));
            let values = ops::<V>()
                .iter()
                .map(|(_, op)| bits(op(va, vb, vc)))
                .collect();
            let masks = [va, vb, va.simd_lt(vb)]
                .iter()
                .map(|m| (m.to_bitmask(), m.any(), m.all()))
                .collect();
            (
                values,
                masks,
                [bits(V::ZERO), bits(V::ONE), bits(V::splat(a[0]))],
            )
        }
        let wide = results::<Wide>(a, b, c);
        let avx = Avx::<I>::outlined(
            #[inline(always)]
            || results::<Avx<I>>(a, b, c),
        );
        for (k, (name, _)) in ops::<Wide>().iter().enumerate() {
            prop_assert_eq!(wide.0[k], avx.0[k], "{}", name);
        }
        prop_assert_eq!(&wide.1, &avx.1);
        prop_assert_eq!(wide.2, avx.2);
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]

        /// The AVX lanes, in the x86-64-v3 and x86-64-v4 copies, compute what `wide`'s lanes
        /// compute, bit for bit, NaN and signed zeros included (each where the processor
        /// runs that copy).
        #[test]
        fn avx_lanes_are_wides_lanes(
            a in [number(), number(), number(), number()],
            b in [number(), number(), number(), number()],
            c in [number(), number(), number(), number()],
        ) {
            if level_of_processor() >= Level::V3 {
                same::<V3>(a, b, c)?;
            }
            if level_of_processor() >= Level::V4 {
                same::<V4>(a, b, c)?;
            }
        }
    }

    /// The vendor CPUID gives is the one Linux reads off it.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_vendor_is_the_one_linux_names() {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").expect("/proc/cpuinfo");
        let vendor = cpuinfo
            .lines()
            .find_map(|line| line.strip_prefix("vendor_id"))
            .and_then(|rest| rest.split(':').nth(1))
            .expect("a vendor_id line")
            .trim();
        assert_eq!(processor_is_intel(), vendor == "GenuineIntel", "{vendor}");
    }

    /// `RAYTREE_CPU_LEVEL` names a level, never a higher one than the processor runs.
    #[test]
    fn levels_are_named_as_stats_prints_them() {
        for level in [Level::Baseline, Level::V3, Level::V4] {
            assert_eq!(Level::named(level.name()), Some(level));
        }
        assert_eq!(Level::named("x86-64-v5"), None);
        assert!(level() <= level_of_processor());
    }
}
