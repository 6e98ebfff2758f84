//! Bad, truncated and corrupted recordings are refused with a typed error that names what is wrong and the
//! byte offset where — never a panic, whatever the bytes.

mod support;

use proptest::prelude::*;
use rebound_record::{Recording, RecordingError};
use support::{frame_starts, small, word};

#[test]
fn a_wrong_magic_is_refused() {
    let mut bytes = small();
    bytes[0] = b'X';
    let error = Recording::read(bytes.as_slice()).unwrap_err();
    assert!(matches!(error, RecordingError::BadMagic { .. }), "{error}");
    assert_eq!(error.offset(), Some(0));
    assert!(error.to_string().contains("not a Rebound recording"));
    let empty = Recording::read(&[][..]).unwrap_err();
    assert!(matches!(empty, RecordingError::BadMagic { ref found, .. } if found.is_empty()));
}

#[test]
fn another_version_is_refused_naming_both_versions() {
    let mut bytes = small();
    bytes[8..12].copy_from_slice(&1u32.to_le_bytes());
    let error = Recording::read(bytes.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::UnsupportedVersion {
                found: 1,
                supported: 2
            }
        ),
        "{error}"
    );
    assert!(error.to_string().contains("version 1"), "{error}");
}

#[test]
fn every_truncation_is_an_error_at_its_offset_or_a_shorter_whole_recording() {
    let bytes = small();
    let starts = frame_starts(&bytes);
    for cut in 0..bytes.len() {
        match Recording::read(&bytes[..cut]) {
            Ok(recording) => {
                let k = starts.iter().position(|&s| s == cut);
                assert_eq!(
                    k,
                    Some(recording.frames().len()),
                    "cut at {cut} read as a whole recording"
                );
            }
            Err(error) => {
                assert!(
                    !starts.contains(&cut),
                    "cut at a frame boundary {cut}: {error}"
                );
                let offset = error.offset().unwrap();
                assert!(
                    offset as usize <= cut,
                    "cut at {cut}, error at {offset}: {error}"
                );
                if cut >= starts[0] {
                    assert!(
                        matches!(error, RecordingError::Truncated { .. }),
                        "cut at {cut}: {error}"
                    );
                    // The frames before the cut are still there.
                    let (partial, error) = Recording::read_lossy(&bytes[..cut]).unwrap();
                    assert!(error.is_some());
                    let whole = starts.iter().filter(|&&s| s <= cut).count() - 1;
                    assert_eq!(partial.frames().len(), whole);
                }
            }
        }
    }
}

#[test]
fn a_broken_manifest_names_the_json_line_and_column() {
    let mut bytes = small();
    bytes[16] = b'[';
    let error = Recording::read(bytes.as_slice()).unwrap_err();
    let RecordingError::Json {
        what,
        offset,
        message,
    } = &error
    else {
        panic!("{error}");
    };
    assert_eq!((*what, *offset), ("manifest", 16));
    assert!(message.contains("line 1 column"), "{message}");
    let mut bytes = small();
    let m = word(&bytes, 12);
    bytes[12..16].copy_from_slice(&(m + 1).to_le_bytes());
    let error = Recording::read(bytes.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadLength {
                what: "manifest length",
                offset: 12,
                ..
            }
        ),
        "{error}"
    );
}

#[test]
fn a_payload_length_that_disagrees_with_its_counts_is_refused_at_the_frame() {
    let bytes = small();
    let start = frame_starts(&bytes)[1];
    let mut bad = bytes.clone();
    // One more body than the payload holds.
    let nb = word(&bad, start + 4 + 16);
    bad[start + 4 + 16..start + 4 + 20].copy_from_slice(&(nb + 1).to_le_bytes());
    let error = Recording::read(bad.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadLength {
                what: "frame payload length",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(error.offset(), Some(start as u64));
    let mut odd = bytes;
    let len = word(&odd, start);
    odd[start..start + 4].copy_from_slice(&(len + 2).to_le_bytes());
    let error = Recording::read(odd.as_slice()).unwrap_err();
    assert!(
        matches!(error, RecordingError::BadLength { found, expected, .. } if found == u64::from(len) + 2 && expected == u64::from(len) + 4),
        "{error}"
    );
}

#[test]
fn bad_fields_are_named_at_their_offsets() {
    let bytes = small();
    let start = frame_starts(&bytes)[3];
    let p = start + 4;
    let nb = word(&bytes, p + 16) as usize;
    let nc = word(&bytes, p + 20) as usize;
    assert!(nc > 0, "the ball touches the ground");
    let flags = p + 84 + 52 * nb;
    let contacts = flags + nb.div_ceil(4) * 4;
    // Body kind 3.
    let mut bad = bytes.clone();
    bad[flags + 1] = 0b1101;
    let error = Recording::read(bad.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadValue {
                field: "body flags",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(error.offset(), Some((flags + 1) as u64));
    // A contact naming a body that does not exist.
    let mut bad = bytes.clone();
    bad[contacts + 4..contacts + 8].copy_from_slice(&99u32.to_le_bytes());
    let error = Recording::read(bad.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadValue {
                field: "contact body B",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(error.offset(), Some((contacts + 4) as u64));
    assert!(error.to_string().contains("99"));
    // A non-finite position.
    let mut bad = bytes.clone();
    bad[p + 84 + 12..p + 84 + 16].copy_from_slice(&f32::NAN.to_le_bytes());
    let error = Recording::read(bad.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadValue {
                field: "body state",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(error.offset(), Some((p + 84 + 12) as u64));
    // An unknown event kind, in the first frame that has events.
    let with_events = frame_starts(&bytes)
        .into_iter()
        .find(|&s| s < bytes.len() && word(&bytes, s + 4 + 28) > 0)
        .unwrap();
    let q = with_events + 4;
    let (nb, nc, nj) = (
        word(&bytes, q + 16) as usize,
        word(&bytes, q + 20) as usize,
        word(&bytes, q + 24) as usize,
    );
    let events =
        q + 84 + word(&bytes, q + 32) as usize + 52 * nb + nb.div_ceil(4) * 4 + 40 * nc + 40 * nj;
    let mut bad = bytes.clone();
    bad[events..events + 4].copy_from_slice(&9u32.to_le_bytes());
    let error = Recording::read(bad.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadValue {
                field: "event kind",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(error.offset(), Some(events as u64));
}

#[test]
fn a_count_that_disagrees_with_the_described_bodies_is_refused() {
    let bytes = small();
    let start = frame_starts(&bytes)[2];
    // A frame with 4 bodies more than the recording has described, and a length that agrees.
    let p = start + 4;
    let nb = word(&bytes, p + 16) as usize;
    let len = word(&bytes, start) as usize;
    let mut bad = bytes[..start].to_vec();
    let grown = len + 4 * 52 + 4;
    bad.extend_from_slice(&(grown as u32).to_le_bytes());
    let mut payload = bytes[p..p + len].to_vec();
    payload[16..20].copy_from_slice(&((nb + 4) as u32).to_le_bytes());
    payload.extend(std::iter::repeat_n(0u8, 4 * 52 + 4));
    bad.extend_from_slice(&payload);
    let error = Recording::read(bad.as_slice()).unwrap_err();
    assert!(
        matches!(
            error,
            RecordingError::BadValue {
                field: "body count",
                ..
            }
        ),
        "{error}"
    );
    assert_eq!(error.offset(), Some((p + 16) as u64));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Random byte changes, insertions and deletions anywhere give a recording or an error, never a panic;
    /// an error's offset lies within the file.
    #[test]
    fn mutated_recordings_never_panic(
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 1..8),
    ) {
        let mut bytes = small();
        for (at, value, kind) in edits {
            let i = at.index(bytes.len().max(1));
            match kind {
                0 if i < bytes.len() => bytes[i] ^= value | 1,
                1 => bytes.insert(i.min(bytes.len()), value),
                _ if i < bytes.len() => { bytes.remove(i); }
                _ => {}
            }
        }
        match Recording::read(bytes.as_slice()) {
            Ok(recording) => prop_assert!(recording.frames().len() <= 6),
            Err(error) => {
                let offset = error.offset().unwrap_or(0);
                prop_assert!(offset <= bytes.len() as u64, "{error} beyond {}", bytes.len());
                prop_assert!(!error.to_string().is_empty());
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Random 32-bit words written over the frames (counts, lengths, indices, flags, floats) give a
    /// recording or an error at an offset within the file, never a panic.
    #[test]
    fn overwritten_frame_words_never_panic(
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u32>()), 1..4),
    ) {
        let mut bytes = small();
        let frames = frame_starts(&bytes)[0];
        for (at, value) in edits {
            let i = frames + at.index(bytes.len() - frames - 3);
            bytes[i..i + 4].copy_from_slice(&value.to_le_bytes());
        }
        if let Err(error) = Recording::read(bytes.as_slice()) {
            prop_assert!(error.offset().unwrap_or(0) <= bytes.len() as u64, "{error}");
        }
    }
}
