//! Least-squares fit of the Gaussian A·exp(−((x − c)/w)²), the form of Eq. 12, to points
//! (x, y) by damped Gauss–Newton (Levenberg–Marquardt), e.g. |F_ad/F_JKR| against α* (Fig. 7).

use std::fmt;

/// Parameters of the Gaussian A·exp(−((x − c)/w)²) (the form of Eq. 12; note: no factor 2 in
/// the exponent, so `width` is √2 times the standard deviation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaussianFit {
    /// Peak value A.
    pub amplitude: f64,
    /// Position c of the peak.
    pub centre: f64,
    /// Width w (positive in a fit result).
    pub width: f64,
}

impl GaussianFit {
    /// Value of the Gaussian at `x`, A·exp(−((x − c)/w)²).
    pub fn eval(&self, x: f64) -> f64 {
        self.amplitude * (-((x - self.centre) / self.width).powi(2)).exp()
    }
}

/// Why [`fit_gaussian`] could not fit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FitError {
    /// Fewer than three distinct abscissae: the three parameters are not determined.
    TooFewPoints {
        /// Number of distinct x values among the points.
        distinct: usize,
    },
    /// A point has a non-finite coordinate (NaN or ±∞).
    NonFinite {
        /// Index of the first such point.
        index: usize,
    },
    /// The starting guess has a non-finite parameter or a zero width.
    BadStart,
    /// The damped normal equations became singular (or non-finite): the points do not
    /// determine the parameters from there (e.g. the Gaussian has collapsed to zero amplitude).
    Singular {
        /// Gauss–Newton iteration (from 0) at which the solve failed.
        iteration: usize,
    },
}

impl fmt::Display for FitError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::TooFewPoints { distinct } => write!(
                f,
                "Gaussian fit needs at least 3 distinct x values, got {distinct}"
            ),
            Self::NonFinite { index } => {
                write!(f, "Gaussian fit: point {index} has a non-finite coordinate")
            }
            Self::BadStart => write!(
                f,
                "Gaussian fit: the starting guess must be finite with a non-zero width"
            ),
            Self::Singular { iteration } => write!(
                f,
                "Gaussian fit: singular normal equations at iteration {iteration}"
            ),
        }
    }
}

impl std::error::Error for FitError {}

/// Least-squares fit of A·exp(−((x − c)/w)²) to `points` (x, y), starting from `start`.
///
/// Damped Gauss–Newton (Levenberg–Marquardt): the diagonal of JᵀJ is scaled by 1 + μ, μ starts
/// at 1e-3, shrinks ×0.3 (down to 1e-12) on a step that lowers the sum of squared residuals and
/// grows ×10 otherwise. It stops after 200 iterations, on an accepted step whose largest
/// component is below 1e-12, or when μ exceeds 1e12; the width is kept positive. The result is
/// the last accepted estimate (a local minimum near `start`: pick `start` near the expected
/// peak, e.g. Eq. 12's (1.023, 0.3619, 0.1188) for Fig. 7).
///
/// # Errors
/// [`FitError::TooFewPoints`] with fewer than 3 distinct x values, [`FitError::NonFinite`] for a
/// NaN or infinite coordinate, [`FitError::BadStart`] for a non-finite start or zero width, and
/// [`FitError::Singular`] if the damped 3×3 normal equations cannot be solved.
///
/// ```
/// use tack_analytics::{GaussianFit, fit_gaussian};
/// let truth = GaussianFit { amplitude: 0.9, centre: 0.3, width: 0.1 };
/// let pts: Vec<(f64, f64)> = (0..20)
///     .map(|i| 0.1 + i as f64 * 0.02)
///     .map(|x| (x, truth.eval(x)))
///     .collect();
/// let start = GaussianFit { amplitude: 1.0, centre: 0.36, width: 0.12 };
/// let fit = fit_gaussian(&pts, start).unwrap();
/// assert!((fit.centre - 0.3).abs() < 1e-10);
/// assert!(fit_gaussian(&pts[..2], start).is_err());
/// ```
pub fn fit_gaussian(points: &[(f64, f64)], start: GaussianFit) -> Result<GaussianFit, FitError> {
    if let Some(index) = points
        .iter()
        .position(|&(x, y)| !x.is_finite() || !y.is_finite())
    {
        return Err(FitError::NonFinite { index });
    }
    let distinct = count_distinct_x(points);
    if distinct < 3 {
        return Err(FitError::TooFewPoints { distinct });
    }
    let GaussianFit {
        amplitude,
        centre,
        width,
    } = start;
    if !(amplitude.is_finite() && centre.is_finite() && width.is_finite()) || width == 0.0 {
        return Err(FitError::BadStart);
    }
    // The arithmetic below is kept in the order of the original Fig. 7 fit (xtask), so that
    // its numbers are reproduced bit for bit.
    let model = |p: [f64; 3], x: f64| p[0] * (-((x - p[1]) / p[2]).powi(2)).exp();
    let cost = |p: [f64; 3]| {
        points
            .iter()
            .map(|&(x, y)| (y - model(p, x)).powi(2))
            .sum::<f64>()
    };
    let mut p = [amplitude, centre, width];
    let mut mu = 1e-3;
    for iteration in 0..200 {
        let (mut jtj, mut jtr) = ([[0.0; 3]; 3], [0.0; 3]);
        for &(x, y) in points {
            let e = (-((x - p[1]) / p[2]).powi(2)).exp();
            let u = (x - p[1]) / p[2];
            let j = [e, p[0] * e * 2.0 * u / p[2], p[0] * e * 2.0 * u * u / p[2]];
            let r = y - p[0] * e;
            for a in 0..3 {
                jtr[a] += j[a] * r;
                for b in 0..3 {
                    jtj[a][b] += j[a] * j[b];
                }
            }
        }
        for (a, row) in jtj.iter_mut().enumerate() {
            row[a] *= 1.0 + mu;
        }
        let Some(step) = solve3(jtj, jtr) else {
            return Err(FitError::Singular { iteration });
        };
        let trial = [p[0] + step[0], p[1] + step[1], (p[2] + step[2]).abs()];
        if cost(trial) < cost(p) {
            let small = step.iter().map(|s| s.abs()).fold(0.0, f64::max) < 1e-12;
            p = trial;
            mu = (mu * 0.3).max(1e-12);
            if small {
                break;
            }
        } else {
            mu *= 10.0;
            if mu > 1e12 {
                break;
            }
        }
    }
    Ok(GaussianFit {
        amplitude: p[0],
        centre: p[1],
        width: p[2],
    })
}

/// Number of distinct x values among `points` (all finite).
fn count_distinct_x(points: &[(f64, f64)]) -> usize {
    let mut xs: Vec<f64> = points.iter().map(|q| q.0).collect();
    xs.sort_by(f64::total_cmp);
    // −0.0 and 0.0 sort apart but are the same abscissa.
    xs.dedup_by(|a, b| a == b);
    xs.len()
}

/// Solves the 3×3 system `m`·x = `r` by Cramer's rule; `None` if |det m| < 1e-300 or det m is
/// not finite.
fn solve3(m: [[f64; 3]; 3], r: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(m);
    if d.abs() < 1e-300 || !d.is_finite() {
        return None;
    }
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let mut mc = m;
        for row in 0..3 {
            mc[row][c] = r[row];
        }
        *o = det(mc) / d;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lambda_star;
    use crate::quad::assert_close;

    /// The starting guess of Fig. 7 (xtask).
    const START: GaussianFit = GaussianFit {
        amplitude: 1.0,
        centre: 0.36,
        width: 0.12,
    };

    fn samples(truth: GaussianFit, xs: impl Iterator<Item = f64>) -> Vec<(f64, f64)> {
        xs.map(|x| (x, truth.eval(x))).collect()
    }

    /// Exact samples have zero residual at the truth, where Gauss–Newton converges
    /// quadratically: the parameters come back to rounding (1e-10 leaves a wide margin).
    #[test]
    fn recovers_parameters_from_exact_samples() {
        for (truth, xs) in [
            (
                GaussianFit {
                    amplitude: 0.9,
                    centre: 0.3,
                    width: 0.1,
                },
                (0..20).map(|i| 0.1 + i as f64 * 0.02).collect::<Vec<_>>(),
            ),
            // Eq. 12 itself, sampled like Fig. 7's α* ≤ 0.4.
            (
                GaussianFit {
                    amplitude: 1.023,
                    centre: 0.3619,
                    width: 0.1188,
                },
                vec![0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4],
            ),
            // Only three points, one side of the peak.
            (
                GaussianFit {
                    amplitude: 1.2,
                    centre: 0.4,
                    width: 0.15,
                },
                vec![0.2, 0.3, 0.35],
            ),
        ] {
            let fit = fit_gaussian(&samples(truth, xs.into_iter()), START).unwrap();
            assert_close(fit.amplitude, truth.amplitude, 1e-10);
            assert_close(fit.centre, truth.centre, 1e-10);
            assert_close(fit.width, truth.width, 1e-10);
        }
    }

    /// `eval` is Eq. 12 for Eq. 12's parameters, bit for bit (same expression).
    #[test]
    fn eval_is_eq12_form() {
        let eq12 = GaussianFit {
            amplitude: 1.023,
            centre: 0.3619,
            width: 0.1188,
        };
        for x in [0.0, 0.2, 0.3619, 0.5, 1.0] {
            assert_eq!(eq12.eval(x), lambda_star(x));
        }
    }

    /// Repeated abscissae count once: 3 points at 2 distinct x are too few.
    #[test]
    fn too_few_points_is_an_error() {
        let truth = START;
        for (pts, distinct) in [
            (vec![], 0),
            (samples(truth, [0.3].into_iter()), 1),
            (samples(truth, [0.3, 0.4].into_iter()), 2),
            (samples(truth, [0.3, 0.4, 0.4, -0.0, 0.0].into_iter()), 3),
        ] {
            let r = fit_gaussian(&pts, START);
            if distinct < 3 {
                assert_eq!(r, Err(FitError::TooFewPoints { distinct }));
                assert!(r.unwrap_err().to_string().contains("at least 3 distinct"));
            } else {
                assert!(r.is_ok(), "{r:?}");
            }
        }
    }

    #[test]
    fn non_finite_input_or_start_is_an_error() {
        let mut pts = samples(START, [0.2, 0.3, 0.4, 0.5].into_iter());
        pts[2].1 = f64::NAN;
        assert_eq!(
            fit_gaussian(&pts, START),
            Err(FitError::NonFinite { index: 2 })
        );
        pts[2] = (f64::INFINITY, 0.5);
        assert_eq!(
            fit_gaussian(&pts, START),
            Err(FitError::NonFinite { index: 2 })
        );
        let pts = samples(START, [0.2, 0.3, 0.4].into_iter());
        for start in [
            GaussianFit {
                width: 0.0,
                ..START
            },
            GaussianFit {
                centre: f64::NAN,
                ..START
            },
        ] {
            assert_eq!(fit_gaussian(&pts, start), Err(FitError::BadStart));
        }
    }

    /// Far in the tail of the start (exp(−((x − c)/w)²) underflows to 0 at every point) the
    /// Jacobian vanishes and the normal equations are singular at the first iteration.
    #[test]
    fn singular_system_is_an_error() {
        let pts = [(100.0, 1.0), (101.0, 2.0), (102.0, 1.0)];
        let r = fit_gaussian(&pts, START);
        assert_eq!(r, Err(FitError::Singular { iteration: 0 }));
        assert!(r.unwrap_err().to_string().contains("singular"));
        // All-zero data at zero amplitude: J has zero columns.
        let zero = GaussianFit {
            amplitude: 0.0,
            ..START
        };
        let pts = [(0.3, 0.0), (0.35, 0.0), (0.4, 0.0)];
        assert_eq!(
            fit_gaussian(&pts, zero),
            Err(FitError::Singular { iteration: 0 })
        );
    }

    #[test]
    fn solve3_solves_and_detects_singular() {
        let m = [[4.0, 1.0, 0.5], [1.0, 3.0, -1.0], [0.5, -1.0, 2.0]];
        let x = [0.25, -1.5, 2.0];
        let r: Vec<f64> = m
            .iter()
            .map(|row| row.iter().zip(&x).map(|(a, b)| a * b).sum())
            .collect();
        let got = solve3(m, [r[0], r[1], r[2]]).unwrap();
        for (g, w) in got.iter().zip(&x) {
            assert!((g - w).abs() < 1e-14, "{got:?}");
        }
        assert!(
            solve3(
                [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]],
                [1.0; 3]
            )
            .is_none()
        );
        assert!(
            solve3(
                [[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
                [1.0; 3]
            )
            .is_none()
        );
    }
}
