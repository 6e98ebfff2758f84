//! How two colliding surfaces' friction and restitution combine into one value per contact. Applied when a
//! contact is created (collision stage), not in the solver.

/// A rule to combine a material property of two surfaces.
///
/// When the two surfaces name different rules, the one later in this list wins (`Max` beats everything),
/// as in rapier.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CombineRule {
    /// `(a + b) / 2`. Default.
    #[default]
    Average,
    /// `√(a·b)` — Box2D's default for friction.
    GeometricMean,
    /// `min(a, b)`.
    Min,
    /// `a·b`.
    Multiply,
    /// `max(a, b)` — Box2D's default for restitution.
    Max,
}

impl CombineRule {
    /// Combines `a` (with rule `rule_a`) and `b` (with `rule_b`) by the stronger of the two rules.
    #[must_use]
    pub fn combine(a: f32, rule_a: Self, b: f32, rule_b: Self) -> f32 {
        match rule_a.max(rule_b) {
            Self::Average => 0.5 * (a + b),
            Self::GeometricMean => (a * b).max(0.0).sqrt(),
            Self::Min => a.min(b),
            Self::Multiply => a * b,
            Self::Max => a.max(b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules() {
        use CombineRule::*;
        let c = |ra, rb| CombineRule::combine(0.25, ra, 1.0, rb);
        assert!((c(Average, Average) - 0.625).abs() < 1e-7);
        assert!((c(GeometricMean, Average) - 0.5).abs() < 1e-7);
        assert!((c(Min, Average) - 0.25).abs() < 1e-7);
        assert!((c(Average, Multiply) - 0.25).abs() < 1e-7);
        assert!((c(Max, Min) - 1.0).abs() < 1e-7);
        assert!(CombineRule::combine(0.0, GeometricMean, 1.0, GeometricMean).abs() < 1e-7);
    }
}
