//! Compile-time square root and logarithm, so that derived constants are computed, not typed in.

/// Square root of `x >= 0` by Newton's method (Heron), usable in `const` context.
///
/// Source: Heron's iteration x ← (x + a/x)/2; 64 steps from a start ≥ √a reach the fixed point
/// for every argument this crate needs (small numbers of order one).
pub(crate) const fn sqrt(a: f64) -> f64 {
    let mut x = if a > 1.0 { a } else { 1.0 };
    let mut i = 0;
    while i < 64 {
        x = 0.5 * (x + a / x);
        i += 1;
    }
    x
}

/// ln(1 + √2) = asinh(1), usable in `const` context.
///
/// Source: ln x = 2 artanh((x − 1)/(x + 1)), and for x = 1 + √2 the argument is z = √2 − 1;
/// the series 2 Σ z^(2k+1)/(2k+1) with z² ≈ 0.17 reaches f64 precision in under 30 terms.
pub(crate) const fn ln_one_plus_sqrt2() -> f64 {
    let z = sqrt(2.0) - 1.0;
    let z2 = z * z;
    let mut term = z;
    let mut sum = 0.0;
    let mut k = 0;
    while k < 40 {
        sum += term / (2 * k + 1) as f64;
        term *= z2;
        k += 1;
    }
    2.0 * sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn const_sqrt_matches_std() {
        for a in [0.0, 0.25, 1.0, 2.0, 3.0, 10.0] {
            assert!((sqrt(a) - a.sqrt()).abs() <= 2.0 * f64::EPSILON * a.sqrt().max(1.0));
        }
    }

    #[test]
    fn const_ln_matches_std_asinh() {
        assert!((ln_one_plus_sqrt2() - 1.0f64.asinh()).abs() < 4.0 * f64::EPSILON);
    }
}
