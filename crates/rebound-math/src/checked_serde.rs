//! `checked_serde!`: serde for a type whose values must pass a check, so that a deserialised value is
//! checked exactly as its constructors and setters check it (one check per type, at every door). Not part of
//! any step stage.
//!
//! The type derives serde with `#[serde(remote = "Self")]`, which makes the derived code inherent functions
//! rather than trait impls; the macro then implements `Serialize` with the derived function and
//! `Deserialize` as the derived function followed by the check, whose error (which names the field and the
//! value) becomes the deserialiser's error. Field attributes (`default`, `with`) work as with a plain derive.
//! Why not `#[serde(try_from = "Raw")]`: it needs a second copy of every field in a raw twin of the type.

/// Implements `serde::Serialize` and a checking `serde::Deserialize` for a type that derives serde with
/// `#[serde(remote = "Self")]`: under the calling crate's `serde` feature, or always with `always` first
/// (for a crate whose serde is not optional).
///
/// `$check` is a function `fn(Self) -> Result<Self, E>` with `E: Display` (the type's `validated`).
///
/// ```ignore
/// #[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(remote = "Self"))]
/// pub struct Rope { max_length: f32 }
/// rebound_math::checked_serde!(Rope, Rope::validated);
/// ```
#[macro_export]
macro_rules! checked_serde {
    (always $ty:ty, $check:expr) => {
        $crate::checked_serde!(@impl $ty, $check);
    };
    ($ty:ty, $check:expr) => {
        #[cfg(feature = "serde")]
        $crate::checked_serde!(@impl $ty, $check);
    };
    (@impl $ty:ty, $check:expr) => {
        impl ::serde::Serialize for $ty {
            fn serialize<S: ::serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                <$ty>::serialize(self, serializer)
            }
        }

        impl<'de> ::serde::Deserialize<'de> for $ty {
            fn deserialize<D: ::serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
                let value = <$ty>::deserialize(deserializer)?;
                ($check)(value).map_err(<D::Error as ::serde::de::Error>::custom)
            }
        }
    };
}
