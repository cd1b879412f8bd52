//! An elastic layer (film) of thickness h on a rigid base: its description and the compliance
//! factor of a Fourier mode relative to the half-space (docs/theory.md §2.5).
//!
//! A surface pressure `p cos(k·x)` on the layer displaces its surface by
//! `S(kh) · 2p/(E* k) · cos(k·x)`, with `2/(E* k)` the half-space's compliance and `S` from
//! [`layer_compliance_factor`]. A 2D Fourier mode of the 3D layer is a plane-strain problem
//! along `k`, solved with the Papkovich–Neuber potentials
//! `ψ_z = (a e^{−kz} + b e^{kz}) cos kx`, `φ = (c e^{−kz} + d e^{kz}) cos kx`, no shear traction
//! on the surface and either a bonded (`u = 0`) or a frictionless (`u_z = 0`, `σ_xz = 0`) base:
//!
//! - bonded: `S = [(3−4ν) sinh 2kh − 2kh] / [(3−4ν) cosh 2kh + 2(kh)² + 5 − 12ν + 8ν²]`;
//! - frictionless: `S = (cosh 2kh − 1) / (sinh 2kh + 2kh)`, independent of ν.

use crate::KernelError;

/// How the layer meets its rigid base.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface {
    /// Welded to the base: both displacement components vanish there.
    Bonded,
    /// Resting on a frictionless base: no normal displacement and no shear traction there.
    Frictionless,
}

impl Interface {
    /// The scene spelling (`body.interface`): `"bonded"` or `"frictionless"`.
    pub fn name(self) -> &'static str {
        match self {
            Interface::Bonded => "bonded",
            Interface::Frictionless => "frictionless",
        }
    }
}

/// An isotropic elastic layer of thickness `thickness` and Poisson ratio `poisson` on a rigid
/// base. Its modulus is the operator's `E* = E/(1 − ν²)` (the indenter is rigid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layer {
    /// Thickness h (field `body.thickness`), finite and > 0.
    pub thickness: f64,
    /// Poisson ratio ν (field `body.poisson`), in (−1, 0.5].
    pub poisson: f64,
    /// The base's contact condition (field `body.interface`).
    pub interface: Interface,
}

impl Layer {
    /// Checks the thickness (finite, > 0) and the Poisson ratio (in (−1, 0.5]).
    pub fn check(&self) -> Result<(), KernelError> {
        if !(self.thickness.is_finite() && self.thickness > 0.0) {
            return Err(KernelError::Thickness(self.thickness));
        }
        if !(self.poisson > -1.0 && self.poisson <= 0.5) {
            return Err(KernelError::Poisson(self.poisson));
        }
        Ok(())
    }

    /// [`layer_compliance_factor`] at wave number `k` (≥ 0).
    pub fn factor(&self, k: f64) -> f64 {
        layer_compliance_factor(k * self.thickness, self.poisson, self.interface)
    }

    /// Surface displacement per unit pressure of the mode of wave number `k > 0`:
    /// `S(kh)·2/(E* k)`.
    pub fn compliance(&self, k: f64, e_star: f64) -> f64 {
        self.factor(k) * 2.0 / (e_star * k)
    }

    /// Displacement per unit pressure of a uniform pressure (the q = 0 mode of a periodic
    /// layer): uniaxial strain, `h(1 − 2ν)/(E*(1 − ν)²)` = `h(1+ν)(1−2ν)/(E(1−ν))`, for either
    /// base (a uniform state has no lateral strain and no shear traction). For a bonded base it
    /// is the limit k → 0 of [`Self::compliance`]; for a frictionless one that limit is `h/E*`
    /// (the film slides, in plane stress along `k`), so the mean mode is discontinuous there.
    pub fn uniform_compliance(&self, e_star: f64) -> f64 {
        let nu = self.poisson;
        self.thickness * (1.0 - 2.0 * nu) / (e_star * (1.0 - nu) * (1.0 - nu))
    }
}

/// The layer's compliance at wave number k over the half-space's `2/(E* k)`, for a normal
/// surface pressure without shear traction, as a function of `kh ≥ 0` (0 at kh = 0, → 1 as
/// kh → ∞). Formulas in the module documentation.
///
/// Evaluated without overflow or cancellation for every `kh ≥ 0` and ν in (−1, 0.5]:
/// numerator and denominator are multiplied by `2e^{−2kh}`, `1 − e^{−2kh}` comes from `expm1`,
/// and the bonded numerator is split into `2(1−2ν) sinh 2kh + (sinh 2kh − 2kh)`, both
/// non-negative, the second summed as a series below kh = 1. Beyond kh = 1000 the factor is 1
/// to the last bit, and kh is clamped there (a NaN kh gives NaN).
pub fn layer_compliance_factor(kh: f64, poisson: f64, interface: Interface) -> f64 {
    let x = kh.clamp(0.0, 1e3);
    if x == 0.0 {
        return 0.0;
    }
    let t = (-2.0 * x).exp();
    let a = -(-2.0 * x).exp_m1(); // 1 − t, accurate for small x
    let sinh2 = a * (2.0 - a); // 2t·sinh 2x = 1 − t²
    match interface {
        Interface::Frictionless => {
            // 2t(cosh 2x − 1) = (1 − t)², 2t(sinh 2x + 2x) = 1 − t² + 4xt.
            a * a / (sinh2 + 4.0 * x * t)
        }
        Interface::Bonded => {
            let nu = poisson;
            // 2t·(sinh 2x − 2x)
            let excess = if x < 1.0 {
                2.0 * t * sinh_minus_identity(2.0 * x)
            } else {
                sinh2 - 4.0 * x * t
            };
            let num = 2.0 * (1.0 - 2.0 * nu) * sinh2 + excess;
            let den = (3.0 - 4.0 * nu) * (1.0 + t * t)
                + (4.0 * x * x + 2.0 * (5.0 - 12.0 * nu + 8.0 * nu * nu)) * t;
            num / den
        }
    }
}

/// `sinh y − y` by its series `Σ y^{2n+1}/(2n+1)!`, n ≥ 1 (all terms positive; for y ≤ 2).
fn sinh_minus_identity(y: f64) -> f64 {
    let y2 = y * y;
    let mut term = y * y2 / 6.0;
    let mut sum = 0.0;
    let mut n = 3.0;
    while term > sum * 1e-17 {
        sum += term;
        term *= y2 / ((n + 1.0) * (n + 2.0));
        n += 2.0;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    const NUS: [f64; 5] = [-0.9, 0.0, 0.3, 0.49, 0.5];

    /// kh from 1e-4 to 1e3, 20 per decade.
    fn khs() -> impl Iterator<Item = f64> {
        (0..=140).map(|i| 10f64.powf(-4.0 + i as f64 / 20.0))
    }

    /// The plane-strain boundary-value problem solved numerically (k = 1, μ = 1, h = kh):
    /// Papkovich–Neuber potentials ψ_z = a e^{−z} + b e^{z−h}, φ = c e^{−z} + d e^{z−h}
    /// (z into the layer, the surface at z = 0), 2μu_x = k(zψ + φ) (times sin x),
    /// 2μu_z = (3−4ν)ψ − zψ' − φ', σ_zz = 2νψ' + 2μu_z' (λ div u = 2νψ'),
    /// σ_xz = μ(u_x' − k u_z). Rows: σ_zz(0) = −1, σ_xz(0) = 0 and the base's two conditions;
    /// Gaussian elimination with partial pivoting. Returns u_z(0)·E*·k/2.
    fn numerical_factor(kh: f64, nu: f64, interface: Interface) -> f64 {
        let (h, mu) = (kh, 1.0);
        // (u_x, u_z, σ_zz, σ_xz) of each of the four basis potentials at depth z.
        let fields = |z: f64| -> [[f64; 4]; 4] {
            let mut out = [[0.0; 4]; 4];
            for (col, o) in out.iter_mut().enumerate() {
                let (s, v) = if col % 2 == 0 {
                    (-1.0, (-z).exp())
                } else {
                    (1.0, (z - h).exp())
                };
                // (ψ, ψ', ψ''), (φ, φ', φ'')
                let (psi, phi) = if col < 2 {
                    ([v, s * v, v], [0.0; 3])
                } else {
                    ([0.0; 3], [v, s * v, v])
                };
                let ux = (z * psi[0] + phi[0]) / (2.0 * mu);
                let dux = (psi[0] + z * psi[1] + phi[1]) / (2.0 * mu);
                let uz = ((3.0 - 4.0 * nu) * psi[0] - z * psi[1] - phi[1]) / (2.0 * mu);
                let duz = ((2.0 - 4.0 * nu) * psi[1] - z * psi[2] - phi[2]) / (2.0 * mu);
                let szz = 2.0 * nu * psi[1] + 2.0 * mu * duz;
                let sxz = mu * (dux - uz);
                *o = [ux, uz, szz, sxz];
            }
            out
        };
        let (top, base) = (fields(0.0), fields(h));
        // Row of one field of the four basis solutions, with its right-hand side.
        let pick = |src: &[[f64; 4]; 4], field: usize, rhs: f64| {
            let mut row = [0.0; 5];
            for (r, s) in row.iter_mut().zip(src) {
                *r = s[field];
            }
            row[4] = rhs;
            row
        };
        let (first, second) = match interface {
            Interface::Bonded => (0, 1),
            Interface::Frictionless => (1, 3),
        };
        let mut m = [
            pick(&top, 2, -1.0),
            pick(&top, 3, 0.0),
            pick(&base, first, 0.0),
            pick(&base, second, 0.0),
        ];
        for col in 0..4 {
            let pivot = (col..4)
                .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
                .unwrap();
            m.swap(col, pivot);
            let pivot_row = m[col];
            for row in m.iter_mut().skip(col + 1) {
                let f = row[col] / pivot_row[col];
                for (r, p) in row.iter_mut().zip(&pivot_row).skip(col) {
                    *r -= f * p;
                }
            }
        }
        let mut coef = [0.0; 4];
        for row in (0..4).rev() {
            let s: f64 = (row + 1..4).map(|c| m[row][c] * coef[c]).sum();
            coef[row] = (m[row][4] - s) / m[row][row];
        }
        let uz0: f64 = (0..4).map(|c| top[c][1] * coef[c]).sum();
        let e_star = 2.0 * mu * (1.0 + nu) / (1.0 - nu * nu);
        uz0 * e_star / 2.0
    }

    #[test]
    fn closed_form_matches_the_numerical_boundary_value_problem() {
        let mut worst: f64 = 0.0;
        for interface in [Interface::Bonded, Interface::Frictionless] {
            for nu in NUS {
                for kh in [0.05, 0.3, 1.0, 2.5, 7.0, 20.0] {
                    let s = layer_compliance_factor(kh, nu, interface);
                    let n = numerical_factor(kh, nu, interface);
                    let rel = (s - n).abs() / n;
                    worst = worst.max(rel);
                    assert!(rel < 1e-10, "{interface:?} ν = {nu} kh = {kh}: {s} vs {n}");
                }
            }
        }
        eprintln!("closed form vs 4×4 solve: worst relative difference {worst:e}");
    }

    #[test]
    fn thick_layers_are_half_spaces() {
        for interface in [Interface::Bonded, Interface::Frictionless] {
            for nu in NUS {
                // 1 − S ≈ 4(kh)²e^{−2kh}/(3 − 4ν): about 1e-14 at kh = 20, exactly 0 far out.
                assert!((layer_compliance_factor(20.0, nu, interface) - 1.0).abs() < 1e-13);
                assert_eq!(layer_compliance_factor(1e3, nu, interface), 1.0);
                assert_eq!(layer_compliance_factor(1e300, nu, interface), 1.0);
                assert_eq!(layer_compliance_factor(f64::INFINITY, nu, interface), 1.0);
            }
        }
    }

    #[test]
    fn thin_bonded_compressible_layer_is_in_uniaxial_strain() {
        // u/p = h(1+ν)(1−2ν)/(E(1−ν)), i.e. S → kh(1−2ν)/(2(1−ν)²); the relative correction is
        // O((kh)²) with a coefficient that grows as ν → 1/2 (the incompressible crossover at
        // kh ~ √(1−2ν)), so ν = 0.49 is tested at smaller kh.
        for (nu, kh, tol) in [(-0.9, 1e-4, 1e-3), (0.0, 1e-4, 1e-3), (0.3, 1e-4, 1e-3)] {
            let s = layer_compliance_factor(kh, nu, Interface::Bonded);
            let thin = kh * (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu) * (1.0 - nu));
            assert!((s / thin - 1.0).abs() < tol, "ν = {nu}: {s} vs {thin}");
            let layer = Layer {
                thickness: 2.0,
                poisson: nu,
                interface: Interface::Bonded,
            };
            let (e_star, k) = (3.0, kh / 2.0);
            let e = e_star * (1.0 - nu * nu);
            let uniaxial = 2.0 * (1.0 + nu) * (1.0 - 2.0 * nu) / (e * (1.0 - nu));
            assert!((layer.compliance(k, e_star) / uniaxial - 1.0).abs() < tol);
            assert!((layer.uniform_compliance(e_star) / uniaxial - 1.0).abs() < 1e-14);
        }
        let s = layer_compliance_factor(1e-6, 0.49, Interface::Bonded);
        let thin = 1e-6 * 0.02 / (2.0 * 0.51 * 0.51);
        assert!((s / thin - 1.0).abs() < 1e-3, "{s} vs {thin}");
    }

    #[test]
    fn thin_bonded_incompressible_layer_follows_the_cubic_law() {
        // u/p = h³k²/(3μ), μ = E/3 for ν = 1/2, i.e. S → (2/3)(kh)³ (1 − 9(kh)²/5 + ...).
        for kh in [1e-4, 1e-3, 1e-2] {
            let s = layer_compliance_factor(kh, 0.5, Interface::Bonded);
            let cubic = 2.0 / 3.0 * kh * kh * kh;
            let rel = (s / cubic - 1.0).abs();
            assert!(rel < 2.0 * kh * kh + 1e-14, "kh = {kh}: rel = {rel}");
        }
        // The same law in physical units.
        let (h, e_star, k) = (0.5, 4.0, 1e-3);
        let layer = Layer {
            thickness: h,
            poisson: 0.5,
            interface: Interface::Bonded,
        };
        let mu = e_star * 0.75 / 3.0;
        let cubic = h * h * h * k * k / (3.0 * mu);
        assert!((layer.compliance(k, e_star) / cubic - 1.0).abs() < 1e-5);
        assert_eq!(layer.uniform_compliance(e_star), 0.0);
    }

    #[test]
    fn thin_frictionless_layer_slides_in_plane_stress() {
        // S → kh/2 (1 − (kh)⁴/45 + ...) for every ν: u/p = h/E* = h(1−ν²)/E.
        for nu in NUS {
            for kh in [1e-4, 1e-2, 0.1] {
                let s = layer_compliance_factor(kh, nu, Interface::Frictionless);
                let rel = (s / (kh / 2.0) - 1.0).abs();
                assert!(
                    rel < kh.powi(4) / 40.0 + 1e-15,
                    "ν = {nu}, kh = {kh}: {rel}"
                );
            }
        }
    }

    #[test]
    fn finite_positive_and_increasing_over_the_whole_range() {
        for interface in [Interface::Bonded, Interface::Frictionless] {
            for nu in NUS {
                let mut last = 0.0;
                for kh in khs() {
                    let s = layer_compliance_factor(kh, nu, interface);
                    assert!(
                        s.is_finite() && s > 0.0,
                        "{interface:?} ν = {nu}, kh = {kh}"
                    );
                    assert!(s >= last, "{interface:?} ν = {nu}, kh = {kh}: {s} < {last}");
                    // A layer on a rigid base is stiffer than the half-space.
                    assert!(s <= 1.0, "{interface:?} ν = {nu}, kh = {kh}: {s}");
                    last = s;
                }
            }
        }
    }

    #[test]
    fn series_and_exponential_branches_agree_at_kh_1() {
        for nu in NUS {
            let below = layer_compliance_factor(1.0 - 1e-15, nu, Interface::Bonded);
            let above = layer_compliance_factor(1.0, nu, Interface::Bonded);
            assert!(
                (below - above).abs() < 1e-14,
                "ν = {nu}: {below} vs {above}"
            );
        }
    }

    #[test]
    fn check_names_the_field() {
        let good = Layer {
            thickness: 1.0,
            poisson: 0.3,
            interface: Interface::Bonded,
        };
        assert!(good.check().is_ok());
        assert!(
            Layer {
                poisson: 0.5,
                ..good
            }
            .check()
            .is_ok()
        );
        for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Layer {
                thickness: h,
                ..good
            }
            .check()
            .unwrap_err();
            assert!(e.to_string().starts_with("body.thickness = "), "{e}");
        }
        for nu in [-1.0, 0.51, f64::NAN] {
            let e = Layer {
                poisson: nu,
                ..good
            }
            .check()
            .unwrap_err();
            assert!(e.to_string().starts_with("body.poisson = "), "{e}");
        }
    }
}
