//! The fixed numbers of the `.rrec` layout (`docs/recording.md`): the magic, the version, the byte sizes of
//! the headers and entries, and the flag bits. Shared by the writer and the reader, so the two cannot drift.

/// The first 8 bytes of every recording: `"RBREC\r\n\x1A"`. The CR LF and Ctrl-Z catch files mangled by a
/// text-mode transfer, as PNG's signature does.
pub const MAGIC: [u8; 8] = *b"RBREC\r\n\x1a";

/// The format version this crate writes and the only one it reads. 2: contact force events (EVENT kind 8
/// and the FORCE block, counted in the frame header's former reserved word).
pub const VERSION: u32 = 2;

/// The file extension of recordings (without the dot).
pub const EXTENSION: &str = "rrec";

/// The index value meaning "no object": the world side of a world joint, an unused event field, a handle
/// the recorder never saw.
pub const NONE: u32 = u32::MAX;

/// The `format` string of every manifest.
pub const FORMAT_NAME: &str = "rebound-recording";

/// Bytes before the manifest: magic, version, manifest length.
pub(crate) const FILE_HEADER_LEN: usize = 16;
/// Bytes of a frame's header.
pub(crate) const FRAME_HEADER_LEN: usize = 84;
/// Bytes per body in a frame, not counting its flag byte: position, rotation, two velocities.
pub(crate) const BODY_LEN: usize = 52;
/// Bytes per contact entry.
pub(crate) const CONTACT_LEN: usize = 40;
/// Bytes per joint entry.
pub(crate) const JOINT_LEN: usize = 40;
/// Bytes per event entry.
pub(crate) const EVENT_LEN: usize = 16;
/// Bytes per contact force entry.
pub(crate) const FORCE_LEN: usize = 40;
/// The EVENT kind of a contact force event, whose details are a FORCE entry.
pub(crate) const CONTACT_FORCE_KIND: u32 = 8;

/// Body flag: the body exists at this frame.
pub(crate) const BODY_PRESENT: u8 = 1;
/// Body flag: the body is asleep.
pub(crate) const BODY_SLEEPING: u8 = 1 << 1;
/// Position of the two kind bits in a body's flags.
pub(crate) const BODY_KIND_SHIFT: u32 = 2;
/// Joint flag: the joint exists at this frame.
pub(crate) const JOINT_PRESENT: u32 = 1;
/// Joint flag: the joint has broken.
pub(crate) const JOINT_BROKEN: u32 = 1 << 1;

/// `n` rounded up to a multiple of 4.
pub(crate) const fn pad4(n: usize) -> usize {
    n.div_ceil(4) * 4
}

/// The exact payload length of a frame with these counts (`docs/recording.md`, "The frame payload"), or
/// `None` if it does not fit in a `usize`.
pub(crate) fn payload_len(
    changes_len: usize,
    bodies: usize,
    contacts: usize,
    joints: usize,
    events: usize,
    forces: usize,
) -> Option<usize> {
    let parts = [
        Some(FRAME_HEADER_LEN),
        Some(changes_len),
        bodies.checked_mul(BODY_LEN),
        bodies.checked_add(3).map(|n| n & !3),
        contacts.checked_mul(CONTACT_LEN),
        joints.checked_mul(JOINT_LEN),
        events.checked_mul(EVENT_LEN),
        forces.checked_mul(FORCE_LEN),
    ];
    parts
        .into_iter()
        .try_fold(0usize, |sum, part| sum.checked_add(part?))
}
