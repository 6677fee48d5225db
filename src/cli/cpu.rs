//! The instructions this build was compiled to use, checked against the CPU it runs on.
//!
//! The default build runs on any x86-64: its fast wing picks AVX2 or SSE2 when it runs. A build
//! made with `-C target-cpu=...` (in RUSTFLAGS, say) uses that CPU's instructions everywhere,
//! and on a CPU without them would stop with an illegal instruction somewhere in a render;
//! this check runs first and says what is missing and how to build the portable program.

/// An x86 feature the compiler may use: its name (as `target_feature` spells it) and where
/// CPUID reports it.
#[cfg(target_arch = "x86_64")]
struct Feature {
    name: &'static str,
    /// Compiled in: the build uses it.
    required: bool,
    /// The register and bit of its CPUID leaf.
    register: Register,
    bit: u32,
}

#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy)]
enum Register {
    /// Leaf 1, ECX.
    Leaf1Ecx,
    /// Leaf 7 sub-leaf 0, EBX.
    Leaf7Ebx,
    /// Leaf 0x8000_0001, ECX.
    ExtendedEcx,
}

/// The CPUID registers the features of the x86-64 levels v2 and v3 are read from, and the
/// state the operating system saves (XCR0): AVX needs the OS to save the YMM registers.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Default)]
struct Cpuid {
    leaf1_ecx: u32,
    leaf7_ebx: u32,
    extended_ecx: u32,
    /// XCR0 bits 1 and 2 (SSE and AVX state) both set.
    os_saves_avx: bool,
}

#[cfg(target_arch = "x86_64")]
macro_rules! feature {
    ($name:literal, $register:ident, $bit:literal) => {
        Feature {
            name: $name,
            required: cfg!(target_feature = $name),
            register: Register::$register,
            bit: $bit,
        }
    };
}

/// The features of x86-64-v2 and v3 that Rust names (LAHF/SAHF it does not), as the Intel
/// and AMD manuals number their CPUID bits.
#[cfg(target_arch = "x86_64")]
const FEATURES: [Feature; 14] = [
    feature!("sse3", Leaf1Ecx, 0),
    feature!("ssse3", Leaf1Ecx, 9),
    feature!("fma", Leaf1Ecx, 12),
    feature!("cmpxchg16b", Leaf1Ecx, 13),
    feature!("sse4.1", Leaf1Ecx, 19),
    feature!("sse4.2", Leaf1Ecx, 20),
    feature!("movbe", Leaf1Ecx, 22),
    feature!("popcnt", Leaf1Ecx, 23),
    feature!("avx", Leaf1Ecx, 28),
    feature!("f16c", Leaf1Ecx, 29),
    feature!("bmi1", Leaf7Ebx, 3),
    feature!("avx2", Leaf7Ebx, 5),
    feature!("bmi2", Leaf7Ebx, 8),
    feature!("lzcnt", ExtendedEcx, 5),
];

/// The features compiled into this build that a CPU with these CPUID registers lacks.
#[cfg(target_arch = "x86_64")]
fn missing(cpu: Cpuid) -> Vec<&'static str> {
    lacking(cpu, FEATURES.iter().filter(|f| f.required))
}

/// Which of `features` a CPU with these CPUID registers lacks.
#[cfg(target_arch = "x86_64")]
fn lacking<'a>(cpu: Cpuid, features: impl Iterator<Item = &'a Feature>) -> Vec<&'static str> {
    features
        .filter(|f| {
            let register = match f.register {
                Register::Leaf1Ecx => cpu.leaf1_ecx,
                Register::Leaf7Ebx => cpu.leaf7_ebx,
                Register::ExtendedEcx => cpu.extended_ecx,
            };
            let present = register & (1 << f.bit) != 0;
            // AVX, AVX2, FMA and F16C use the YMM registers, which the OS must save.
            let needs_os = matches!(f.name, "avx" | "avx2" | "fma" | "f16c");
            !present || (needs_os && !cpu.os_saves_avx)
        })
        .map(|f| f.name)
        .collect()
}

/// Reads the CPU's registers. `is_x86_feature_detected!` cannot be asked: for a feature the
/// build enables it answers "yes" at compile time, without looking at the CPU.
#[cfg(target_arch = "x86_64")]
fn read_cpuid() -> Cpuid {
    use std::arch::x86_64::{__cpuid, __cpuid_count, _xgetbv};
    // SAFETY: CPUID exists on every x86-64 CPU; leaves past the maximum reported are not read.
    unsafe {
        let max = __cpuid(0).eax;
        let max_extended = __cpuid(0x8000_0000).eax;
        let leaf1_ecx = __cpuid(1).ecx;
        let leaf7_ebx = if max >= 7 { __cpuid_count(7, 0).ebx } else { 0 };
        let extended_ecx = if max_extended >= 0x8000_0001 {
            __cpuid(0x8000_0001).ecx
        } else {
            0
        };
        // XGETBV exists when the OS has enabled XSAVE (OSXSAVE, leaf 1 ECX bit 27).
        let os_saves_avx = leaf1_ecx & (1 << 27) != 0 && _xgetbv(0) & 0b110 == 0b110;
        Cpuid {
            leaf1_ecx,
            leaf7_ebx,
            extended_ecx,
            os_saves_avx,
        }
    }
}

/// `Err` with a message naming what this CPU lacks, when the build uses instructions it does
/// not have.
pub fn check() -> Result<(), String> {
    #[cfg(target_arch = "x86_64")]
    {
        let missing = missing(read_cpuid());
        if !missing.is_empty() {
            return Err(format!(
                "this build of raytree uses instructions this CPU does not have ({}).\n\
                 Build the portable program, which picks its instructions when it runs, \
                 without `-C target-cpu` in RUSTFLAGS:\n  \
                 cargo build --release",
                missing.join(", ")
            ));
        }
    }
    Ok(())
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::*;

    /// The registers of a CPU with every feature of x86-64-v3 (bits from the manuals).
    fn v3() -> Cpuid {
        Cpuid {
            leaf1_ecx: 1
                | 1 << 9
                | 1 << 12
                | 1 << 13
                | 1 << 19
                | 1 << 20
                | 1 << 22
                | 1 << 23
                | 1 << 27
                | 1 << 28
                | 1 << 29,
            leaf7_ebx: 1 << 3 | 1 << 5 | 1 << 8,
            extended_ecx: 1 << 5,
            os_saves_avx: true,
        }
    }

    #[test]
    fn a_v3_cpu_lacks_nothing() {
        assert_eq!(lacking(v3(), FEATURES.iter()), Vec::<&str>::new());
        assert_eq!(missing(v3()), Vec::<&str>::new());
    }

    #[test]
    fn a_cpu_without_avx2_is_told_so_when_the_build_uses_it() {
        let cpu = Cpuid {
            leaf7_ebx: v3().leaf7_ebx & !(1 << 5),
            ..v3()
        };
        // A build for x86-64-v3 uses every feature in the table.
        assert_eq!(lacking(cpu, FEATURES.iter()), vec!["avx2"]);
        let expected: Vec<&str> = if cfg!(target_feature = "avx2") {
            vec!["avx2"]
        } else {
            vec![]
        };
        assert_eq!(missing(cpu), expected);
    }

    #[test]
    fn avx_is_missing_when_the_os_does_not_save_its_registers() {
        let cpu = Cpuid {
            os_saves_avx: false,
            ..v3()
        };
        assert_eq!(
            lacking(cpu, FEATURES.iter()),
            vec!["fma", "avx", "f16c", "avx2"]
        );
        let expected: Vec<&str> = ["fma", "avx", "f16c", "avx2"]
            .into_iter()
            .filter(|name| FEATURES.iter().any(|f| f.name == *name && f.required))
            .collect();
        assert_eq!(missing(cpu), expected);
    }

    #[test]
    fn the_build_runs_on_the_machine_that_tests_it() {
        assert_eq!(check(), Ok(()));
    }
}
