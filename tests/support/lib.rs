//! Support code shared by the workspace-level scenario tests (`tests/`) and whole-scene benches (`benches/`).
//!
//! Not part of the engine: nothing here is published. It holds what SCENES.md defines once for every scene —
//! the random generator — and the analytic predictors the tests compare against — and the peer scenes
//! themselves ([`scenes`]), which the scene tests, the criterion benches (`benches/scenes.rs`) and the
//! `compare` binary (`benches/compare/`) share.

pub mod demos;
pub mod scenes;

/// The scene generator of SCENES.md: xorshift64*.
///
/// ```text
/// next: s ^= s >> 12; s ^= s << 25; s ^= s >> 27; return s · 0x2545F4914F6CDD1D (wrapping)
/// U(lo, hi) = lo + (hi − lo)·((next >> 40) / 2^24)   in f32
/// ```
///
/// It is reproduced bit for bit in the rapier peer project, so both engines build identical scenes.
#[derive(Debug, Clone)]
pub struct XorShift64Star {
    state: u64,
}

impl XorShift64Star {
    /// A generator seeded with `seed`; a zero seed (a fixed point of xorshift) is replaced by 1.
    #[must_use]
    pub const fn new(seed: u64) -> Self {
        Self {
            state: if seed == 0 { 1 } else { seed },
        }
    }

    /// The next 64-bit output.
    pub fn next_u64(&mut self) -> u64 {
        let mut s = self.state;
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        self.state = s;
        s.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A uniform `f32` in `[lo, hi)` from the top 24 bits of the next output.
    pub fn uniform(&mut self, lo: f32, hi: f32) -> f32 {
        let unit = (self.next_u64() >> 40) as f32 / (1u64 << 24) as f32;
        lo + (hi - lo) * unit
    }
}

/// Position after `steps` steps of semi-implicit (symplectic) Euler under constant acceleration, each step
/// split into `substeps` substeps of `h = dt / substeps`:
///
/// ```text
/// v ← v + a·h;  x ← x + v·h     (per substep)
/// x_n = x₀ + v₀·t + a·h²·n(n+1)/2,   n = steps·substeps, t = n·h
/// ```
///
/// This is the closed form the free-fall tests compare the engine against (not the continuous `½·a·t²`,
/// which the integrator only approaches as h → 0).
#[must_use]
pub fn symplectic_euler_position(
    x0: f64,
    v0: f64,
    a: f64,
    dt: f64,
    steps: u32,
    substeps: u32,
) -> f64 {
    let n = f64::from(steps) * f64::from(substeps);
    let h = dt / f64::from(substeps);
    x0 + v0 * n * h + a * h * h * n * (n + 1.0) / 2.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generator_is_the_documented_xorshift64_star() {
        // First output for seed 1, computed by hand from the recurrence:
        // s = 1 ^ (1 >> 12) = 1; s ^= 1 << 25 → 0x2000001; s ^= s >> 27 → 0x2000001.
        let mut g = XorShift64Star::new(1);
        assert_eq!(
            g.next_u64(),
            0x2000001u64.wrapping_mul(0x2545_F491_4F6C_DD1D)
        );
        let mut g = XorShift64Star::new(0xBA11_5EED_0000_0001);
        for _ in 0..1000 {
            let u = g.uniform(-0.04, 0.04);
            assert!((-0.04..0.04).contains(&u));
        }
    }

    #[test]
    fn predictor_matches_a_direct_loop() {
        let (mut x, mut v) = (10.0f64, 1.0f64);
        let (dt, substeps) = (1.0 / 60.0, 4);
        let h = dt / f64::from(substeps);
        for _ in 0..(120 * substeps) {
            v += -9.81 * h;
            x += v * h;
        }
        let predicted = symplectic_euler_position(10.0, 1.0, -9.81, dt, 120, substeps);
        assert!((x - predicted).abs() < 1e-9, "{x} vs {predicted}");
    }
}
