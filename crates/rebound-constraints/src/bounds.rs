//! Impulse bounds, force ranges and break limits that may be infinite (serde helpers for the types that hold
//! them). Not part of a step stage.
//!
//! JSON has no infinity (serde_json writes `null` for ±∞, which a plain `f32` cannot read back), so a value
//! that may be ±∞ is written as a number when finite and as the string `"inf"` or `"-inf"` when not. Reading
//! accepts a number, those strings (also `"+inf"`, `"infinity"`, `"-infinity"`) and `null`, which stands for
//! the side's own infinity (+∞ for an upper bound or a break limit, −∞ for a lower bound): files written
//! before the strings existed load unchanged. RON's bare `inf` is a number and reads as one. The public API
//! keeps `f32` with ±∞ = "no bound": the values are compared against forces in the solver, where ∞ needs no
//! special case.

#[cfg(feature = "serde")]
use serde::{Deserializer, Serializer};

/// Writes `value` as a number, or as `"inf"` / `"-inf"`.
#[cfg(feature = "serde")]
fn write<S: Serializer>(value: f32, serializer: S) -> Result<S::Ok, S::Error> {
    if value.is_finite() || value.is_nan() {
        serializer.serialize_f32(value)
    } else if value > 0.0 {
        serializer.serialize_str("inf")
    } else {
        serializer.serialize_str("-inf")
    }
}

/// Reads a number, an infinity string, or `null` (read as `if_null`).
#[cfg(feature = "serde")]
fn read<'de, D: Deserializer<'de>>(deserializer: D, if_null: f32) -> Result<f32, D::Error> {
    struct Bound(f32);
    impl<'de> serde::de::Visitor<'de> for Bound {
        type Value = f32;

        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str(r#"a number, "inf", "-inf" or null"#)
        }

        fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<f32, E> {
            #[expect(
                clippy::cast_possible_truncation,
                reason = "the engine's values are f32"
            )]
            Ok(v as f32)
        }

        fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<f32, E> {
            Ok(v as f32)
        }

        fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<f32, E> {
            Ok(v as f32)
        }

        fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<f32, E> {
            match v {
                "inf" | "+inf" | "infinity" | "+infinity" => Ok(f32::INFINITY),
                "-inf" | "-infinity" => Ok(f32::NEG_INFINITY),
                _ => Err(E::invalid_value(serde::de::Unexpected::Str(v), &self)),
            }
        }

        fn visit_unit<E: serde::de::Error>(self) -> Result<f32, E> {
            Ok(self.0)
        }

        fn visit_none<E: serde::de::Error>(self) -> Result<f32, E> {
            Ok(self.0)
        }

        fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<f32, D::Error> {
            read(d, self.0)
        }
    }
    deserializer.deserialize_any(Bound(if_null))
}

/// An upper bound or a break limit that may be +∞ (`null` reads as +∞).
#[cfg(feature = "serde")]
pub(crate) mod unbounded {
    use serde::{Deserializer, Serializer};

    /// The value of a limit that is not given: +∞.
    pub(crate) fn infinity() -> f32 {
        f32::INFINITY
    }

    #[expect(
        clippy::trivially_copy_pass_by_ref,
        reason = "serde's `with` signature"
    )]
    pub(crate) fn serialize<S: Serializer>(value: &f32, serializer: S) -> Result<S::Ok, S::Error> {
        super::write(*value, serializer)
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f32, D::Error> {
        super::read(deserializer, f32::INFINITY)
    }
}

/// A lower bound that may be −∞ (`null` reads as −∞).
#[cfg(feature = "serde")]
pub(crate) mod unbounded_below {
    pub(crate) use super::unbounded::serialize;
    use serde::Deserializer;

    /// The value of a lower bound that is not given: −∞.
    pub(crate) fn negative_infinity() -> f32 {
        f32::NEG_INFINITY
    }

    pub(crate) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f32, D::Error> {
        super::read(deserializer, f32::NEG_INFINITY)
    }
}
