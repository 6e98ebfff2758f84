//! Impulse bounds and break limits that may be infinite, written as `null` in JSON (serde helpers for the
//! types that hold them). Not part of a step stage.

/// Serialises a limit that may be +∞ (unbreakable, an upper impulse bound) as `null`, which JSON can carry
/// (it has no infinity), and reads `null` back as +∞.
#[cfg(feature = "serde")]
pub(crate) mod unbounded {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// The value of a limit that is not given: +∞.
    pub(crate) fn infinity() -> f32 {
        f32::INFINITY
    }

    pub(crate) fn serialize<S: Serializer>(value: &f32, serializer: S) -> Result<S::Ok, S::Error> {
        let finite = value.is_finite().then_some(*value);
        finite.serialize(serializer)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f32, D::Error> {
        Ok(Option::<f32>::deserialize(deserializer)?.unwrap_or(f32::INFINITY))
    }
}

/// [`unbounded`] for a lower impulse bound: −∞ as `null`, and back.
#[cfg(feature = "serde")]
pub(crate) mod unbounded_below {
    pub(crate) use super::unbounded::serialize;
    use serde::{Deserialize, Deserializer};

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f32, D::Error> {
        Ok(Option::<f32>::deserialize(deserializer)?.unwrap_or(f32::NEG_INFINITY))
    }
}
