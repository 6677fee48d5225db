//! The parallel loader (`scene/split.rs`) against the one-thread parse: for every text, the
//! same scene or the same error, whatever the number of threads. Shared by the cargo-fuzz
//! target `split` and by `tests/fuzz_parse.rs` on stable Rust.

use std::sync::OnceLock;

use raytree::scene::{parse, Limits};

/// The loader cuts only files of at least this size (`scene::split::MIN_SPLIT_BYTES`).
pub const SPLIT_BYTES: usize = 64 * 1024;

fn pool(threads: usize) -> &'static rayon::ThreadPool {
    static POOLS: [OnceLock<rayon::ThreadPool>; 4] = [
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
        OnceLock::new(),
    ];
    POOLS[threads - 1].get_or_init(|| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(move |i| format!("fuzz-split-{threads}-{i}"))
            .build()
            .expect("a thread pool")
    })
}

/// What loading `text` on `threads` threads gives, as text to compare.
fn load(text: &str, threads: usize) -> String {
    pool(threads).install(
        || match parse(text, "split.yaml", None, &Limits::default()) {
            Ok(scene) => format!("{scene:?}"),
            Err(e) => format!("error {e}"),
        },
    )
}

/// Panics when loading `text` on 2, 3 or 4 threads differs from loading it on one.
pub fn check(text: &str) {
    let one = load(text, 1);
    for threads in 2..=4 {
        let many = load(text, threads);
        if many != one {
            let cut = |s: &str| s.chars().take(300).collect::<String>();
            panic!(
                "{threads} threads differ from one:\n  1: {}\n  {threads}: {}",
                cut(&one),
                cut(&many)
            );
        }
    }
}

/// A fuzzer's bytes as a scene file large enough to be cut: either the text itself, padded
/// with a comment; or, when it holds NUL bytes, `head NUL item NUL tail` with `item` repeated
/// under an `objects:` key until the file is large enough.
pub fn text_of(data: &[u8]) -> Option<String> {
    let text = std::str::from_utf8(data).ok()?;
    let mut parts = text.splitn(3, '\0');
    let (head, item, tail) = (parts.next()?, parts.next(), parts.next());
    Some(match (item, tail) {
        (Some(item), tail) if !item.trim().is_empty() => {
            let mut out = format!("{head}\nobjects:\n");
            while out.len() < SPLIT_BYTES {
                out += item;
                out += "\n";
            }
            out + tail.unwrap_or("")
        }
        _ => format!("{text}\n#{}\n", " ".repeat(SPLIT_BYTES)),
    })
}
