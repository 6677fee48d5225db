//! The most memory the process has held at once (its peak resident set), for `render --stats`.

/// Peak resident memory in bytes: `VmHWM` of /proc/self/status. None where the system does not
/// report it (other than Linux).
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_vm_hwm(&status)
}

/// The `VmHWM:  123456 kB` line of a /proc status text, in bytes.
fn parse_vm_hwm(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut words = line.split_whitespace().skip(1);
    let kib: u64 = words.next()?.parse().ok()?;
    (words.next() == Some("kB")).then_some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_high_water_mark_in_bytes() {
        let status =
            "Name:\traytree\nVmPeak:\t  900000 kB\nVmHWM:\t  123456 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(parse_vm_hwm(status), Some(123_456 * 1024));
        assert_eq!(parse_vm_hwm("VmRSS:\t 1000 kB\n"), None);
        assert_eq!(parse_vm_hwm("VmHWM:\t 12 MB\n"), None);
    }

    /// On Linux the process itself has a peak of at least the 8 MB this test touches.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_process_reports_its_peak() {
        let touched = vec![1u8; 8 << 20];
        let peak = peak_resident_bytes().expect("Linux reports VmHWM");
        assert!(peak >= touched.len() as u64, "{peak}");
        assert_eq!(touched.iter().map(|&b| b as usize).sum::<usize>(), 8 << 20);
    }
}
