//! The process's allocator: the system's, except that a large block (an image's pixels, a
//! mesh's triangles, a BVH) is mapped on its own, aligned to 2 MiB and marked for transparent
//! huge pages.
//!
//! A fresh block of memory costs a page fault the first time each of its pages is written,
//! and in a virtual machine a fault costs some 20 µs. The pixels of an 800×600 image
//! (11.5 MB of f64 triples) are 2 800 pages of 4 KiB: about 56 ms of processor time, a tenth
//! of a whole render of the Whitted peer scene. In pages of 2 MiB they are six faults. Linux
//! backs a region with huge pages only where the system allows it (`madvise` mode or
//! `always`) and only for the parts of it aligned to 2 MiB, hence the alignment; elsewhere
//! the advice is ignored and the block behaves as any other.
//!
//! A mapping is zero when it is made, so `alloc_zeroed` of a large block writes nothing, and a
//! large block shrinks where it is (a mesh's arrays are shrunk to fit once built).

use std::alloc::{GlobalAlloc, Layout, System};
use std::ptr;

/// The size of a huge page on x86-64 and of the alignment of a large block.
const HUGE_PAGE: usize = 2 << 20;

/// Blocks of this size and more are mapped on their own. Half a huge page: such a block costs
/// 256 faults in pages of 4 KiB and one in a huge page, and the rounding up to whole huge
/// pages at most doubles it.
const LARGE: usize = HUGE_PAGE / 2;

/// The global allocator of the `raytree` binary (see the module's comment).
pub struct HugePages;

fn is_large(layout: &Layout) -> bool {
    layout.size() >= LARGE && layout.align() <= HUGE_PAGE
}

/// The bytes mapped for a large block of `size` bytes: whole huge pages.
fn mapped(size: usize) -> usize {
    size.next_multiple_of(HUGE_PAGE)
}

/// Maps `mapped(size)` bytes starting on a huge page's boundary, or returns null. The kernel
/// aligns a mapping only to 4 KiB, so one huge page more is mapped and the ends around the
/// aligned block are given back.
unsafe fn map(size: usize) -> *mut u8 {
    let length = mapped(size);
    let Some(padded) = length.checked_add(HUGE_PAGE) else {
        return ptr::null_mut();
    };
    // SAFETY: an anonymous private mapping at an address of the kernel's choosing touches no
    // existing memory.
    let start = unsafe {
        libc::mmap(
            ptr::null_mut(),
            padded,
            libc::PROT_READ | libc::PROT_WRITE,
            libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
            -1,
            0,
        )
    };
    if start == libc::MAP_FAILED {
        return ptr::null_mut();
    }
    let (head, block, tail) = aligned_within(start as usize);
    // SAFETY: the head and the tail lie inside the mapping just made, outside the block.
    unsafe {
        if head > 0 {
            libc::munmap(start, head);
        }
        if tail > 0 {
            libc::munmap((block + length) as *mut libc::c_void, tail);
        }
        // Advice only: where huge pages are not to be had the block keeps 4 KiB pages.
        libc::madvise(block as *mut libc::c_void, length, libc::MADV_HUGEPAGE);
    }
    block as *mut u8
}

/// Where a block on a huge page's boundary starts in a mapping one huge page longer than the
/// block, made at `start` (page-aligned): the bytes before it, its start, the bytes after it.
fn aligned_within(start: usize) -> (usize, usize, usize) {
    let block = start.next_multiple_of(HUGE_PAGE);
    let head = block - start;
    (head, block, HUGE_PAGE - head)
}

/// Gives back a block `map(size)` made.
unsafe fn unmap(block: *mut u8, size: usize) {
    // SAFETY: the caller passes a block of `map` and the size it was made for.
    unsafe { libc::munmap(block as *mut libc::c_void, mapped(size)) };
}

// SAFETY: every block is either the system allocator's (small layouts, given back to it) or a
// mapping of its own of at least the layout's size, aligned to 2 MiB and so to any alignment
// `is_large` admits; which of the two is decided by the layout alone, which the caller passes
// unchanged to `dealloc` and `realloc`.
unsafe impl GlobalAlloc for HugePages {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if is_large(&layout) {
            unsafe { map(layout.size()) }
        } else {
            unsafe { System.alloc(layout) }
        }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if is_large(&layout) {
            unsafe { map(layout.size()) }
        } else {
            unsafe { System.alloc_zeroed(layout) }
        }
    }

    unsafe fn dealloc(&self, block: *mut u8, layout: Layout) {
        if is_large(&layout) {
            unsafe { unmap(block, layout.size()) }
        } else {
            unsafe { System.dealloc(block, layout) }
        }
    }

    unsafe fn realloc(&self, block: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: the caller guarantees that `new_size`, rounded to the alignment, does not
        // overflow.
        let new_layout = unsafe { Layout::from_size_align_unchecked(new_size, layout.align()) };
        match (is_large(&layout), is_large(&new_layout)) {
            (false, false) => unsafe { System.realloc(block, layout, new_size) },
            (true, true) if mapped(new_size) <= mapped(layout.size()) => {
                // The block stays where it is; whole huge pages past its new end go back.
                let (kept, had) = (mapped(new_size), mapped(layout.size()));
                if kept < had {
                    unsafe { libc::munmap(block.add(kept) as *mut libc::c_void, had - kept) };
                }
                block
            }
            _ => {
                let moved = unsafe { self.alloc(new_layout) };
                if !moved.is_null() {
                    unsafe {
                        ptr::copy_nonoverlapping(block, moved, layout.size().min(new_size));
                        self.dealloc(block, layout);
                    }
                }
                moved
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layout(size: usize, align: usize) -> Layout {
        Layout::from_size_align(size, align).unwrap()
    }

    /// Writes a pattern over every byte of the block; `check` reads it back, so a block smaller
    /// than its layout, or overlapping another, shows.
    unsafe fn fill(block: *mut u8, size: usize, seed: u8) {
        let bytes = unsafe { std::slice::from_raw_parts_mut(block, size) };
        for (i, b) in bytes.iter_mut().enumerate() {
            *b = seed.wrapping_add((i % 251) as u8);
        }
    }

    unsafe fn check(block: *const u8, size: usize, seed: u8) {
        let bytes = unsafe { std::slice::from_raw_parts(block, size) };
        for (i, &b) in bytes.iter().enumerate() {
            assert_eq!(b, seed.wrapping_add((i % 251) as u8), "byte {i} of {size}");
        }
    }

    /// The block lies on a huge page's boundary, wholly inside the mapping (one huge page
    /// longer than the block), and the head and the tail given back are the rest of it.
    #[test]
    fn the_block_is_aligned_inside_its_mapping() {
        for start in (0..=HUGE_PAGE).step_by(4096).map(|s| s + 7 * HUGE_PAGE) {
            let (head, block, tail) = aligned_within(start);
            assert_eq!(block % HUGE_PAGE, 0, "start {start:#x}");
            assert_eq!(block, start + head);
            assert_eq!(head + tail, HUGE_PAGE);
        }
    }

    /// The address range of the mapping (in /proc/self/maps) holding `address`.
    fn mapping_of(address: usize) -> std::ops::Range<usize> {
        let maps = std::fs::read_to_string("/proc/self/maps").unwrap();
        maps.lines()
            .filter_map(|line| {
                let (lo, hi) = line.split_whitespace().next()?.split_once('-')?;
                let range =
                    usize::from_str_radix(lo, 16).ok()?..usize::from_str_radix(hi, 16).ok()?;
                range.contains(&address).then_some(range)
            })
            .next()
            .expect("the block is mapped")
    }

    /// Small blocks are the system's; large ones start on a huge page's boundary, read as
    /// zeros when asked for zeros, and hold what is written anywhere in them.
    #[test]
    fn large_blocks_are_aligned_zeroed_and_whole() {
        let a = HugePages;
        for (size, align) in [
            (24, 8),
            (LARGE - 1, 8),
            (LARGE, 8),
            (LARGE + 1, 64),
            (11_520_000, 8),
            (LARGE, HUGE_PAGE),
            (LARGE, 2 * HUGE_PAGE),
        ] {
            let l = layout(size, align);
            unsafe {
                let zeroed = a.alloc_zeroed(l);
                assert!(!zeroed.is_null());
                assert_eq!(
                    zeroed as usize % align,
                    0,
                    "{size} bytes aligned to {align}"
                );
                if is_large(&l) {
                    assert_eq!(zeroed as usize % HUGE_PAGE, 0, "{size} bytes");
                }
                let bytes = std::slice::from_raw_parts(zeroed, size);
                assert!(bytes.iter().all(|&b| b == 0), "{size} bytes zeroed");
                let plain = a.alloc(l);
                fill(zeroed, size, 1);
                fill(plain, size, 2);
                check(zeroed, size, 1);
                check(plain, size, 2);
                a.dealloc(zeroed, l);
                a.dealloc(plain, l);
            }
        }
    }

    /// Growing and shrinking across the line between small and large keeps the contents,
    /// within the same huge pages and into new ones; a large block shrinks where it is.
    #[test]
    fn realloc_keeps_the_contents_across_sizes() {
        let a = HugePages;
        let sizes = [
            1000,
            LARGE - 1,
            LARGE,
            LARGE + 10,
            mapped(LARGE + 10),
            mapped(LARGE + 10) + 1,
            5 * HUGE_PAGE + 3,
            LARGE + 1,
            3000,
        ];
        unsafe {
            let mut l = layout(sizes[0], 16);
            let mut block = a.alloc(l);
            fill(block, l.size(), 7);
            for &size in &sizes[1..] {
                let kept = l.size().min(size);
                let before = block;
                block = a.realloc(block, l, size);
                assert!(!block.is_null());
                if is_large(&l) && size >= LARGE && size < l.size() {
                    assert_eq!(
                        block,
                        before,
                        "{} bytes shrunk to {size} in place",
                        l.size()
                    );
                }
                assert_eq!(block as usize % 16, 0);
                l = layout(size, 16);
                if is_large(&l) {
                    let mapping = mapping_of(block as usize);
                    assert!(
                        mapping.end >= block as usize + mapped(size),
                        "{size} bytes mapped"
                    );
                }
                check(block, kept, 7);
                fill(block, size, 7);
            }
            a.dealloc(block, l);
        }
    }
}
