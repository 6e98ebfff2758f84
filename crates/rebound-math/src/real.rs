//! The real functions the simulation calls that IEEE 754 does not require to be correctly rounded: sine,
//! cosine, arctangent, exponential, logarithm, hypotenuse. Every crate of the engine calls them here, never
//! through `f32`'s methods (clippy's `disallowed_methods` refuses those in the engine's crates, see
//! `clippy.toml`).
//!
//! `f32::sin` and the others call the platform's maths library, whose last bit differs between platforms
//! (glibc, musl, the MSVC runtime, Apple's libm) and may change between its versions. With the
//! `enhanced-determinism` feature these functions call the `libm` crate instead — a port of musl's, the same
//! Rust code on every platform — so that the same calls give the same bits everywhere; without it they call
//! `std`, which is what the default build wants (the platform's library is usually faster).
//!
//! What needs no such care: `+ − × ÷` and `sqrt` are correctly rounded by IEEE 754 on every platform, and
//! Rust never contracts `a·b + c` into a fused multiply-add unless asked to (`f32::mul_add`, which the engine
//! does not call: `disallowed_methods` refuses it too). glam's own functions that use these (quaternion from
//! an axis and angle, `angle_between`, `slerp`) go through libm under glam's `libm` feature, which
//! `enhanced-determinism` turns on together with its `scalar-math` (no SIMD paths whose results depend on the
//! instruction set).

#![allow(
    clippy::disallowed_methods,
    reason = "the one place that calls the platform's maths library"
)]

/// `sin(x)`, `x` in radians.
#[inline]
#[must_use]
pub fn sin(x: f32) -> f32 {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::sinf(x)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        x.sin()
    }
}

/// `cos(x)`, `x` in radians.
#[inline]
#[must_use]
pub fn cos(x: f32) -> f32 {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::cosf(x)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        x.cos()
    }
}

/// `(sin(x), cos(x))`, `x` in radians.
#[inline]
#[must_use]
pub fn sin_cos(x: f32) -> (f32, f32) {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::sincosf(x)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        x.sin_cos()
    }
}

/// The angle of the point `(x, y)` from the +x axis, in `[−π, π]` (radians).
#[inline]
#[must_use]
pub fn atan2(y: f32, x: f32) -> f32 {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::atan2f(y, x)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        y.atan2(x)
    }
}

/// `eˣ`.
#[inline]
#[must_use]
pub fn exp(x: f32) -> f32 {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::expf(x)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        x.exp()
    }
}

/// The natural logarithm `ln(x)`.
#[inline]
#[must_use]
pub fn ln(x: f32) -> f32 {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::logf(x)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        x.ln()
    }
}

/// `√(x² + y²)` without overflow or underflow in the squares.
#[inline]
#[must_use]
pub fn hypot(x: f32, y: f32) -> f32 {
    #[cfg(feature = "enhanced-determinism")]
    {
        libm::hypotf(x, y)
    }
    #[cfg(not(feature = "enhanced-determinism"))]
    {
        x.hypot(y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    /// Within a few units in the last place of the exact values, under either implementation.
    const TOLERANCE: f32 = 4.0 * f32::EPSILON;

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() <= TOLERANCE * b.abs().max(1.0)
    }

    #[test]
    fn known_values() {
        assert!(close(sin(FRAC_PI_2), 1.0));
        assert!(close(cos(PI), -1.0));
        let (s, c) = sin_cos(FRAC_PI_4);
        assert!(close(s, core::f32::consts::FRAC_1_SQRT_2));
        assert!(close(c, core::f32::consts::FRAC_1_SQRT_2));
        assert!(close(atan2(1.0, -1.0), 3.0 * FRAC_PI_4));
        assert!(close(atan2(-0.0, -1.0), -PI));
        assert!(close(exp(1.0), core::f32::consts::E));
        assert!(close(ln(core::f32::consts::E), 1.0));
        assert!(close(hypot(3.0, 4.0), 5.0));
        assert!(close(hypot(3e30, 4e30), 5e30));
    }

    #[test]
    fn sin_cos_is_sin_and_cos() {
        for k in -100..=100 {
            let x = k as f32 * 0.173;
            let (s, c) = sin_cos(x);
            assert!(close(s, sin(x)) && close(c, cos(x)), "x = {x}");
        }
    }
}
