//! Every law against its own statements: the registry round-trips and matches the scene
//! field, and each smooth curve's work, slope, peak and reach against quadrature, differences
//! and sampling of its own pressure (so a new curve is checked without a new test).

use super::*;

/// Every smooth law of the registry, at a parameter of 2 (not 1, so a γ/ℓ mix-up shows): a
/// length of 2, or the smoothed Dugdale law's σ0 = 2 bound at γ = 1 to elements of 0.05 on a
/// unit modulus (range 0.5, ramp ±0.22).
fn curves() -> Vec<AdhesionLaw> {
    AdhesionLaw::models()
        .filter_map(|m| AdhesionLaw::from_model(m, 2.0))
        .filter(AdhesionLaw::is_smooth)
        .map(|l| l.on_mesh(1.0, 1.0, 0.05))
        .collect()
}

#[test]
fn every_model_round_trips_and_the_scene_field_lists_them() {
    let models: Vec<&str> = AdhesionLaw::models().collect();
    for (i, m) in models.iter().enumerate() {
        assert!(!models[..i].contains(m), "{m} listed twice");
        let law = AdhesionLaw::from_model(m, 0.25).expect("a listed model");
        assert_eq!(law.name(), *m);
        assert_eq!(law.parameter().1, 0.25, "{m}");
        assert!(!law.meaning().is_empty(), "{m}");
    }
    assert_eq!(AdhesionLaw::from_model("morse", 1.0), None);
    let field = fields::field(fields::ADHESION_MODEL).expect("the scene field");
    let fields::Kind::Choice(choices) = field.kind else {
        panic!("{:?}", field.kind)
    };
    assert_eq!(
        choices,
        &models[..],
        "the scene field's choices are the registry's"
    );
    assert_eq!(
        curves().len(),
        3,
        "the exponential, Lennard-Jones and smoothed Dugdale laws"
    );
}

/// The work of separation `∫₀^∞ −p(g) dg` is γ: Simpson's rule in `u = ln(1 + g/ℓ)` up to
/// `g = 10⁴ℓ` (the 9–3 law's tail beyond is `(4/3)γ(ℓ/g)² ≈ 1.3e-8 γ`), 2·10⁴ intervals:
/// the rule's own error is below 1e-10, so 1e-7 is the tail's bound with a margin.
#[test]
fn every_smooth_law_does_the_work_of_adhesion() {
    let gamma = 0.3;
    for law in curves() {
        let (c, l) = (law.curve().unwrap(), law.range(gamma).unwrap());
        let (n, top) = (20_000, (1.0 + 1e4f64).ln());
        let h = top / n as f64;
        let f = |u: f64| -c.pressure(gamma, l * (u.exp() - 1.0)) * l * u.exp();
        let mut sum = f(0.0) + f(top);
        for i in 1..n {
            sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
        }
        let work = sum * h / 3.0;
        assert!(
            (work / gamma - 1.0).abs() < 1e-7,
            "{}: work {work}",
            law.name()
        );
    }
}

/// `stiffness` is `dp/dg` (central differences of step 1e-5ℓ: error ~1e-10 relative to the
/// peak slope, 1e-7 allowed), `peak` the greatest tension (sampled every 1e-5ℓ to 20ℓ and
/// refined: 1e-9), `reach` where the tension falls to [`REACH_FRACTION`] of it (1e-9), and
/// `stiffens` says whether the slope is negative anywhere.
#[test]
fn every_smooth_law_states_its_own_slope_peak_and_reach() {
    let gamma = 0.3;
    for law in curves() {
        let (c, l, name) = (law.curve().unwrap(), law.range(gamma).unwrap(), law.name());
        let scale = c.peak(gamma) / l;
        let mut negative = false;
        let mut best = (0.0f64, 0.0f64);
        for i in 0..2_000_000 {
            let g = i as f64 * 1e-5 * l;
            let t = -c.pressure(gamma, g);
            if t > best.1 {
                best = (g, t);
            }
            if i % 1000 == 1 {
                let e = 1e-5 * l;
                let slope = (c.pressure(gamma, g + e) - c.pressure(gamma, g - e)) / (2.0 * e);
                let stated = c.stiffness(gamma, g);
                assert!((slope - stated).abs() < 1e-7 * scale, "{name} at {g}");
                negative |= stated < 0.0;
            }
        }
        assert_eq!(negative, c.stiffens(), "{name}");
        let peak = c.peak(gamma);
        assert!(
            best.1 <= peak * (1.0 + 1e-12),
            "{name}: {} > {peak}",
            best.1
        );
        assert!(
            (best.1 / peak - 1.0).abs() < 1e-9,
            "{name}: {} vs {peak}",
            best.1
        );
        let reach = law.reach(gamma).unwrap();
        let at = -c.pressure(gamma, reach) / peak;
        assert!(
            (at / REACH_FRACTION - 1.0).abs() < 1e-6,
            "{name}: {at} at the reach"
        );
        assert_eq!(law.peak_tension(gamma, 1.0, 0.1), peak, "{name}");
    }
}

/// A law with a zone ahead of the contact declares its column (`n_cohesive`, saying what it
/// counts); the zero-range criterion, which has none, declares no column.
#[test]
fn every_law_with_a_zone_declares_its_column() {
    for m in AdhesionLaw::models() {
        let law = AdhesionLaw::from_model(m, 0.25).expect("a listed model");
        match (law.family(), law.step_column()) {
            (Family::Criterion { .. }, None) => {}
            (Family::Cohesive { .. }, Some(c)) => {
                assert_eq!(c.name, ZONE_COLUMN);
                assert!(c.meaning.contains("cohesive zone"), "{m}: {}", c.meaning);
            }
            (Family::Smooth(_), Some(c)) => {
                assert_eq!(c.name, ZONE_COLUMN);
                assert!(c.meaning.contains("process zone"), "{m}: {}", c.meaning);
                assert!(c.meaning.contains("beyond 1% of"), "{m}: {}", c.meaning);
            }
            (f, c) => panic!("{m}: {f:?} declares {c:?}"),
        }
    }
}

/// A built-in curve with one statement broken, to check that [`AdhesionLaw::custom`] refuses
/// it and names the method.
#[derive(Debug)]
struct Broken {
    /// The curve it wraps.
    inner: AdhesionLaw,
    name: &'static str,
    /// Factors of the pressure, the stiffness, the peak and the reach.
    pressure: f64,
    stiffness: f64,
    peak: f64,
    reach: f64,
    /// `Some`: what `stiffens` says instead of the truth.
    stiffens: Option<bool>,
    /// The pressure and stiffness at γ = 1 whatever γ is asked.
    ignore_gamma: bool,
    /// NaN beyond twice the reach.
    nan_beyond: bool,
    /// NaN beyond a third of the reach (inside it).
    nan_inside: bool,
    /// Factor of the pressure `pressure_and_stiffness` gives.
    pair: f64,
    /// What `falls_past_peak` says.
    falls: bool,
}

impl Broken {
    fn of(inner: AdhesionLaw) -> Self {
        Self {
            inner,
            name: "broken",
            pressure: 1.0,
            stiffness: 1.0,
            peak: 1.0,
            reach: 1.0,
            stiffens: None,
            ignore_gamma: false,
            nan_beyond: false,
            nan_inside: false,
            pair: 1.0,
            falls: false,
        }
    }
}

impl Curve for Broken {
    fn name(&self) -> &'static str {
        self.name
    }
    fn label(&self) -> &'static str {
        "broken, range l"
    }
    fn length(&self) -> f64 {
        self.inner.curve().unwrap().length()
    }
    fn meaning(&self) -> &'static str {
        "a test curve"
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        if (self.nan_beyond && g > 2.0 * Curve::reach(self))
            || (self.nan_inside && g > Curve::reach(self) / 3.0)
        {
            return f64::NAN;
        }
        let gamma = if self.ignore_gamma { 1.0 } else { gamma };
        self.pressure * self.inner.curve().unwrap().pressure(gamma, g)
    }
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        let gamma = if self.ignore_gamma { 1.0 } else { gamma };
        self.stiffness * self.pressure * self.inner.curve().unwrap().stiffness(gamma, g)
    }
    fn pressure_and_stiffness(&self, gamma: f64, g: f64) -> (f64, f64) {
        (
            self.pair * self.pressure(gamma, g),
            self.stiffness(gamma, g),
        )
    }
    fn stiffens(&self) -> bool {
        self.stiffens
            .unwrap_or_else(|| self.inner.curve().unwrap().stiffens())
    }
    fn peak(&self, gamma: f64) -> f64 {
        self.peak * self.pressure * self.inner.curve().unwrap().peak(gamma)
    }
    fn reach(&self) -> f64 {
        self.reach * self.inner.curve().unwrap().reach()
    }
    fn falls_past_peak(&self) -> bool {
        self.falls
    }
}

/// The built-in smooth curves pass every check a custom curve must pass (so the tolerances
/// refuse no law the solver runs), and the same curve under its own name runs as a custom law.
#[test]
fn the_built_in_curves_pass_the_custom_checks() {
    for law in curves() {
        custom::check_shape(law.curve().unwrap()).unwrap_or_else(|e| panic!("{e}"));
        let custom = AdhesionLaw::custom(Broken::of(law.clone())).unwrap();
        assert!(custom.is_smooth());
        assert_eq!(custom.name(), "broken");
        assert_eq!(custom, custom.clone(), "clones are one curve");
        let other = AdhesionLaw::custom(Broken::of(law.clone())).unwrap();
        assert_ne!(custom, other, "two curves are two laws");
    }
}

/// Each broken statement is refused with the method at fault named.
#[test]
fn a_custom_curve_that_breaks_a_statement_is_refused_naming_the_method() {
    let exp = AdhesionLaw::from(Exponential { range: 2.0 });
    let lj = AdhesionLaw::from(LennardJones { range: 2.0 });
    let cases: [(Broken, &str, &str); 16] = [
        (
            Broken {
                name: "",
                ..Broken::of(exp.clone())
            },
            "Curve::name",
            "non-empty",
        ),
        (
            Broken {
                ignore_gamma: true,
                ..Broken::of(exp.clone())
            },
            "Curve::pressure",
            "scales as γ",
        ),
        (
            Broken {
                nan_beyond: true,
                ..Broken::of(lj.clone())
            },
            "Curve::reach",
            "not finite",
        ),
        // Inside the reach the failing method is named at the gap where it fails (it was
        // blamed on the reach).
        (
            Broken {
                nan_inside: true,
                ..Broken::of(exp.clone())
            },
            "Curve::pressure",
            "is not finite at g = ",
        ),
        (
            Broken {
                pair: 1.0 + 1e-9,
                ..Broken::of(exp.clone())
            },
            "Curve::pressure_and_stiffness",
            "their values",
        ),
        (
            Broken {
                stiffness: -1.0,
                ..Broken::of(lj.clone())
            },
            "Curve::stiffness",
            "dp/dg",
        ),
        (
            Broken {
                reach: 0.0,
                ..Broken::of(exp.clone())
            },
            "Curve::reach",
            "finite and > 0",
        ),
        (
            Broken {
                name: "exponential",
                ..Broken::of(exp.clone())
            },
            "Curve::name",
            "built-in",
        ),
        (
            Broken {
                name: "Morse law",
                ..Broken::of(exp.clone())
            },
            "Curve::name",
            "lowercase",
        ),
        (
            Broken {
                stiffness: -1.0,
                ..Broken::of(exp.clone())
            },
            "Curve::stiffens",
            "is false",
        ),
        (
            Broken {
                stiffness: 1.01,
                ..Broken::of(lj.clone())
            },
            "Curve::stiffness",
            "dp/dg",
        ),
        (
            Broken {
                stiffens: Some(false),
                ..Broken::of(lj.clone())
            },
            "Curve::stiffens",
            "is false",
        ),
        (
            Broken {
                pressure: 2.0,
                ..Broken::of(exp.clone())
            },
            "Curve::pressure",
            "work",
        ),
        (
            Broken {
                peak: 1.1,
                ..Broken::of(exp.clone())
            },
            "Curve::peak",
            "greatest tension",
        ),
        (
            Broken {
                reach: 0.5,
                ..Broken::of(exp.clone())
            },
            "Curve::reach",
            "crops",
        ),
        (
            Broken {
                pressure: f64::NAN,
                ..Broken::of(exp.clone())
            },
            "Curve::peak",
            "finite",
        ),
    ];
    let step = AdhesionLaw::custom(Step).unwrap_err();
    let stepped = [(step, "Curve::pressure", "continuous")];
    let broken = cases
        .into_iter()
        .map(|(c, m, s)| (AdhesionLaw::custom(c).unwrap_err(), m, s));
    for (e, method, says) in broken.chain(stepped) {
        let SolverError::Curve { method: m, .. } = &e else {
            panic!("{e}")
        };
        let text = e.to_string();
        assert_eq!(*m, method, "{text}");
        assert!(text.contains(says), "{method}: {text}");
        assert!(text.starts_with("custom adhesion law"), "{text}");
    }
}

/// The Dugdale law written as a curve: `p = −1` for `g < 1`, 0 beyond (work 1, peak 1, zero
/// slope): its jump lies between samples and only its slope's integral shows it.
#[derive(Debug)]
struct Step;

impl Curve for Step {
    fn name(&self) -> &'static str {
        "step"
    }
    fn label(&self) -> &'static str {
        "a step, range h0"
    }
    fn length(&self) -> f64 {
        1.0
    }
    fn meaning(&self) -> &'static str {
        "a test curve"
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        if g < 0.9876 { -gamma / 0.9876 } else { 0.0 }
    }
    fn stiffness(&self, _gamma: f64, _g: f64) -> f64 {
        0.0
    }
    fn stiffens(&self) -> bool {
        false
    }
    fn peak(&self, gamma: f64) -> f64 {
        gamma / 0.9876
    }
    fn reach(&self) -> f64 {
        2.0
    }
}

/// Beyond `Traction::quiet_beyond` every built-in law's tension stays at or below the cut (the
/// gap itself and gaps 0.1% apart to a thousand lengths beyond it), and 1e-4 of a length short
/// of it the tension is above 0.99 of the cut: the bound is tight as well as safe, down to
/// cuts of 1e-12 of the peak (a step window's, `HELD_FRACTION` of Newton's tolerance). A cut
/// that is not positive and finite gets none; so does a custom curve unless it promises the
/// falling tail ([`Curve::falls_past_peak`]), and then it gets the built-in's bound.
#[test]
fn the_quiet_gap_bounds_the_tail() {
    let gamma = 3.0;
    for law in curves() {
        let t = Traction::new(law.clone(), gamma).unwrap();
        let curve = law.curve().unwrap();
        let (length, peak_gap) = (curve.length(), law.peak_gap().unwrap());
        for fraction in [1e-2, 1e-7, 1e-12] {
            let cut = fraction * curve.peak(gamma);
            let q = t.quiet_beyond(cut, peak_gap).expect("a built-in curve");
            assert!(q > peak_gap, "{law:?}: {q}");
            let mut g = q;
            while g < q + 1e3 * length {
                assert!(t.pressure(g).abs() <= cut, "{law:?} at {g} beyond {q}");
                g += 1e-3 * (g - peak_gap).max(length);
            }
            let short = t.pressure(q - 1e-4 * length).abs();
            assert!(short > 0.99 * cut, "{law:?}: {short} against {cut}");
        }
        for cut in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(t.quiet_beyond(cut, peak_gap), None);
        }
    }
    // The built-in curves under a name of their own: nothing promised, no bound; promised
    // (and checked), the built-in's bound to the bit.
    for law in curves() {
        let peak_gap = law.peak_gap().unwrap();
        let cut = 1e-7 * law.curve().unwrap().peak(gamma);
        let builtin = Traction::new(law.clone(), gamma).unwrap();
        let silent = AdhesionLaw::custom(Broken::of(law.clone())).unwrap();
        let silent = Traction::new(silent, gamma).unwrap();
        assert_eq!(silent.quiet_beyond(cut, peak_gap), None, "{law:?}");
        let promised = Broken {
            falls: true,
            ..Broken::of(law.clone())
        };
        let promised = Traction::new(AdhesionLaw::custom(promised).unwrap(), gamma).unwrap();
        assert_eq!(
            promised.quiet_beyond(cut, peak_gap),
            builtin.quiet_beyond(cut, peak_gap),
            "{law:?}"
        );
    }
}

/// Two wells: half the exponential law of range 1 and half a Gaussian well of width 1 at
/// g = 10, `p = −γ[½e^(−g) + ½ e^(−(g−10)²/2)/√(2π)]`, work γ. Its tension is greatest at the
/// wall, falls to 2.3e-3 of it at g = 6.3 and rises again to 0.4 of it at g = 10: it stiffens
/// on the way.
#[derive(Debug)]
struct TwoWells {
    falls: bool,
}

impl TwoWells {
    /// The pressure and the stiffness at `g` for work `gamma`.
    fn at(gamma: f64, g: f64) -> (f64, f64) {
        let e = 0.5 * (-g).exp();
        let b = 0.5 * (-0.5 * (g - 10.0).powi(2)).exp() / (2.0 * std::f64::consts::PI).sqrt();
        (-gamma * (e + b), gamma * (e + b * (g - 10.0)))
    }
}

impl Curve for TwoWells {
    fn name(&self) -> &'static str {
        "two_wells"
    }
    fn label(&self) -> &'static str {
        "two wells, range l"
    }
    fn length(&self) -> f64 {
        1.0
    }
    fn meaning(&self) -> &'static str {
        "a test curve"
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        Self::at(gamma, g).0
    }
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        Self::at(gamma, g).1
    }
    fn stiffens(&self) -> bool {
        true
    }
    fn peak(&self, gamma: f64) -> f64 {
        -self.pressure(gamma, 0.0)
    }
    /// The Gaussian half at 1e-8 of the peak 0.5.
    fn reach(&self) -> f64 {
        10.0 + (2.0 * (0.2 / 5e-9f64).ln()).sqrt()
    }
    fn falls_past_peak(&self) -> bool {
        self.falls
    }
}

/// A curve that promises a falling tail it does not have is refused, naming the promise and
/// where the curve breaks it; the same curve without the promise runs, with no quiet gap.
#[test]
fn a_false_promise_of_a_falling_tail_is_refused() {
    let err = AdhesionLaw::custom(TwoWells { falls: true })
        .unwrap_err()
        .to_string();
    assert!(err.contains("Curve::falls_past_peak"), "{err}");
    assert!(err.contains("the stiffness is"), "{err}");
    let law = AdhesionLaw::custom(TwoWells { falls: false }).unwrap();
    assert_eq!(law.peak_gap(), Some(0.0));
    let t = Traction::new(law, 1.0).unwrap();
    assert_eq!(t.quiet_beyond(1e-3, 0.0), None);
}
