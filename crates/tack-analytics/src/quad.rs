//! Composite quadrature rules: the tests' checks of closed forms against numerical integrals,
//! and the steady-crack integrals of `viscous_crack`.

/// Composite Simpson rule of `f` on `[a, b]` with `n` (rounded up to even) sub-intervals.
///
/// Source: standard composite Simpson rule, error O(h⁴ f⁗) for smooth integrands.
pub(crate) fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let n = n + n % 2;
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(a) + f(b) + inner) * h / 3.0
}

/// Central finite difference of `f` at `x` with step `h`.
#[cfg(test)]
pub(crate) fn derivative(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    (f(x + h) - f(x - h)) / (2.0 * h)
}

/// Assert `actual` equals `expected` to within the relative tolerance `rel`.
#[cfg(test)]
pub(crate) fn assert_close(actual: f64, expected: f64, rel: f64) {
    let tol = rel * expected.abs().max(1.0e-300);
    assert!(
        (actual - expected).abs() <= tol,
        "actual {actual} vs expected {expected} (rel. tol. {rel})"
    );
}
