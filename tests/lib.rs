//! Shared scenarios for the end-to-end tests and the benchmarks: the smooth JKR sphere.

use tack_analytics::{jkr_force_from_approach, jkr_pull_off_force, jkr_pull_off_radius};
use tack_geometry::{Boundary, Grid, Sphere, Surface};
use tack_kernels::operator_for;
use tack_solver::{AdhesiveOptions, AdhesiveSolver, ApproachPath, PathResult, SnapshotRequest};

/// A smooth sphere in JKR units (R = E* = γ = 1, so â = a, d̂ = d, F̂ = F).
pub struct JkrSphere {
    /// Resolution: JKR pull-off contact radius over element size.
    pub ac_over_dx: f64,
    /// Pohrt–Popov constant κ.
    pub kappa: f64,
    /// Deepest dimensionless approach of the load phase (6 by default: a contact of about
    /// 1.6 a_c, docs/theory.md §3.5).
    pub max_approach: f64,
    /// Dimensionless retraction step.
    pub unload_step: f64,
    /// Dimensionless retraction step while the force is compressive (`None`: `unload_step`).
    pub coarse_unload_step: Option<f64>,
}

/// Outcome of a smooth-sphere load–unload path.
pub struct JkrRun {
    /// The path.
    pub result: PathResult,
    /// Grid used.
    pub grid: Grid,
    /// Greatest tensile force over F_JKR, minus one.
    pub pull_off_error: f64,
    /// Approach of the last step that still had contact.
    pub last_contact_approach: f64,
    /// Largest bonded extent from the centre, in elements (must stay inside the grid).
    pub max_extent: usize,
    /// Largest |F − F_JKR(d)|/|F_JKR| on the peeling branch, d̂ ∈ [−1.5, 1.5] of the unload.
    pub curve_error: f64,
}

impl JkrSphere {
    /// Paper settings at the given resolution.
    pub fn new(ac_over_dx: f64, kappa: f64) -> Self {
        Self {
            ac_over_dx,
            kappa,
            max_approach: 6.0,
            unload_step: 0.01,
            coarse_unload_step: None,
        }
    }

    /// Runs the path on a free grid just large enough for the deepest contact.
    pub fn run(&self) -> JkrRun {
        let a_c = jkr_pull_off_radius(1.0, 1.0, 1.0);
        let dx = a_c / self.ac_over_dx;
        // Loading is nearly Hertzian (a ≈ sqrt(R d)); adhesion adds a ring: 1.25·sqrt(d) holds it.
        let half = (1.25 * self.max_approach.sqrt() / dx).ceil() as usize;
        let grid = Grid::square(2 * half + 1, dx, Boundary::Free).unwrap();
        let surface = Surface::from_shape(grid, &Sphere::new(1.0).unwrap());
        let op = operator_for(grid, 1.0).unwrap();
        let options = AdhesiveOptions::default();

        let mut solver = AdhesiveSolver::new(op, &surface, 1.0, self.kappa, options).unwrap();
        let path = ApproachPath {
            start: self.max_approach / 20.0,
            max_approach: self.max_approach,
            load_step: self.max_approach / 20.0,
            unload_step: self.unload_step,
            coarse_unload_step: self.coarse_unload_step,
            refine_pull_off: false,
            retract_to: None,
            max_steps: 100_000,
        };
        let mut max_extent = 0;
        struct Extent<'a>(&'a mut usize);
        impl tack_solver::Observer for Extent<'_> {
            fn on_step(&mut self, _: usize, _: tack_solver::Phase, r: &tack_solver::StepRecord) {
                *self.0 = (*self.0).max(r.n_bonded);
            }
        }
        let result = solver
            .run_path(&path, &SnapshotRequest::None, &mut Extent(&mut max_extent))
            .unwrap();
        let pull_off_error = result.pull_off_force() / jkr_pull_off_force(1.0, 1.0) - 1.0;
        let last_contact_approach = result
            .records
            .iter()
            .rev()
            .find(|r| r.n_bonded > 0)
            .map_or(f64::NAN, |r| r.approach);
        // Equivalent radius of the largest bonded set, in elements.
        let max_extent = ((max_extent as f64 / std::f64::consts::PI).sqrt()).ceil() as usize;
        let curve_error = result
            .records
            .iter()
            .zip(&result.phases)
            .filter(|(r, p)| {
                **p == tack_solver::Phase::Unload && (-1.5..=1.5).contains(&r.approach)
            })
            .filter_map(|(r, _)| {
                jkr_force_from_approach(1.0, 1.0, 1.0, r.approach).map(|f| (r.force - f).abs())
            })
            .fold(0.0, f64::max)
            / jkr_pull_off_force(1.0, 1.0).abs();
        JkrRun {
            curve_error,
            result,
            grid,
            pull_off_error,
            last_contact_approach,
            max_extent,
        }
    }
}
