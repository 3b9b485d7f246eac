//! The ground-motion records shipped in `assets/records/`, compiled into
//! the binary (and the Python extension), so that a preset's record is
//! there wherever the program runs: from a copied binary, after
//! `cargo install`, or from a moved checkout.
//!
//! A config names one as `shipped:NAME` (`file_h = "shipped:kobe-1995.dat"`):
//! a name that cannot be mistaken for a file on disk, so that
//! `summary.json` repeats the run from any folder and a user's own file of
//! the same name is never taken for it. Its `crc32_h` is the CRC-32 of the
//! shipped bytes, so a rerun by a binary that ships other bytes under the
//! same name is refused, as a changed file is.

/// How a config names a shipped record: this prefix, then the file's name.
pub use crate::sim::scenario::SHIPPED_PREFIX as PREFIX;

/// `(file name, bytes)` of every shipped record (see
/// `assets/records/README.md` for what they are and where they come from).
pub const RECORDS: &[(&str, &[u8])] = &[
    (
        "elcentro-1940-ns.dat",
        include_bytes!("../../assets/records/elcentro-1940-ns.dat"),
    ),
    ("kobe-1995.dat", include_bytes!("../../assets/records/kobe-1995.dat")),
];

/// The file name in a `shipped:NAME` reference (`None` for any other text,
/// which is a path on disk).
pub fn name_of(reference: &str) -> Option<&str> {
    reference.strip_prefix(PREFIX)
}

/// The bytes of shipped record `name` (`kobe-1995.dat`).
pub fn get(name: &str) -> Option<&'static [u8]> {
    RECORDS.iter().find(|(n, _)| *n == name).map(|(_, b)| *b)
}

/// Every shipped record as it is referenced, `shipped:NAME`, for messages.
pub fn references() -> Vec<String> {
    RECORDS.iter().map(|(n, _)| format!("{PREFIX}{n}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every file of `assets/records/` that is a record is shipped, and
    /// every shipped record is the file's bytes (the folder also holds its
    /// README and a suite list).
    #[test]
    fn every_record_of_the_folder_is_shipped() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/records");
        let mut on_disk: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".dat") || n.to_ascii_lowercase().ends_with(".at2"))
            .collect();
        on_disk.sort();
        let shipped: Vec<String> = RECORDS.iter().map(|(n, _)| n.to_string()).collect();
        assert_eq!(on_disk, shipped);
        for (name, bytes) in RECORDS {
            assert_eq!(std::fs::read(format!("{dir}/{name}")).unwrap(), *bytes, "{name}");
        }
        assert_eq!(name_of("shipped:kobe-1995.dat"), Some("kobe-1995.dat"));
        assert_eq!(name_of("kobe-1995.dat"), None);
        assert!(get("kobe-1995.dat").is_some() && get("nope.dat").is_none());
    }
}
