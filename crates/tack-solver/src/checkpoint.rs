//! Copies of an adhesive solver's state between steps, to go back to an earlier approach and
//! retrace it (the refined retraction of [`ApproachPath::refine_pull_off`](crate::ApproachPath)).

use ndarray::Array2;

use crate::{AdhesionLaw, AdhesiveSolver, SolverError};

/// Everything an [`AdhesiveSolver`] carries from one step to the next: the pressure, gap and
/// displacement, the bonded set, the Dugdale law's cohesive zone, the secant predictor's
/// previous step and, under a smooth law, whether the step landed (the next step's predictor
/// and Newton's reach depend on it). Restoring it makes the next step exactly (bit for bit)
/// what it would have been right after the step it was saved at; the solver's scratch
/// (sub-grid operators, CG vectors) holds nothing a step reads before writing it.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverState {
    pressure: Array2<f64>,
    gap: Array2<f64>,
    disp: Array2<f64>,
    bonded: Array2<bool>,
    zone: Option<Array2<bool>>,
    history: Option<(Array2<f64>, f64)>,
    last_approach: Option<f64>,
    landed: Option<bool>,
    /// The law it was saved under: a state restores only into a solver of the same law.
    law: AdhesionLaw,
}

impl SolverState {
    /// The pressure field of the saved state.
    pub fn pressure(&self) -> &Array2<f64> {
        &self.pressure
    }
    /// The bonded mask of the saved state.
    pub fn bonded(&self) -> &Array2<bool> {
        &self.bonded
    }
    /// The approach of the step the state was saved after (`None` before the first step).
    pub fn approach(&self) -> Option<f64> {
        self.last_approach
    }
}

/// `to = from`, reusing `to`'s buffer when the shapes agree.
fn copy<T: Clone>(to: &mut Array2<T>, from: &Array2<T>) {
    if to.dim() == from.dim() {
        to.assign(from);
    } else {
        *to = from.clone();
    }
}

impl AdhesiveSolver {
    /// A copy of the solver's state (see [`SolverState`]).
    ///
    /// ```
    /// use tack_geometry::{Boundary, Grid, Sphere, Surface};
    /// use tack_solver::{AdhesiveOptions, AdhesiveSolver, KAPPA};
    /// let grid = Grid::square(16, 0.25, Boundary::Free)?;
    /// let surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
    /// let op = tack_kernels::operator_for(grid, 1.0)?;
    /// let mut solver = AdhesiveSolver::new(op, &surface, 1.0, KAPPA, AdhesiveOptions::default())?;
    /// solver.step(0.5)?;
    /// let saved = solver.save_state();
    /// let a = solver.step(0.2)?;
    /// solver.restore_state(&saved)?;
    /// let b = solver.step(0.2)?;
    /// assert_eq!(a, b);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn save_state(&self) -> SolverState {
        SolverState {
            pressure: self.base.pressure.clone(),
            gap: self.base.gap.clone(),
            disp: self.base.work.disp.clone(),
            bonded: self.bonded.clone(),
            zone: self.cohesive.as_ref().map(|c| c.zone.clone()),
            history: self.history.clone(),
            last_approach: self.last_approach,
            landed: self.smooth.as_ref().map(|s| s.landed),
            law: self.law().clone(),
        }
    }

    /// [`AdhesiveSolver::save_state`] into `state`, reusing its buffers.
    pub fn save_state_into(&self, state: &mut SolverState) {
        copy(&mut state.pressure, &self.base.pressure);
        copy(&mut state.gap, &self.base.gap);
        copy(&mut state.disp, &self.base.work.disp);
        copy(&mut state.bonded, &self.bonded);
        match (state.zone.as_mut(), self.cohesive.as_ref()) {
            (Some(to), Some(c)) => copy(to, &c.zone),
            (_, c) => state.zone = c.map(|c| c.zone.clone()),
        }
        match (&mut state.history, &self.history) {
            (Some((p, d)), Some((q, e))) => {
                copy(p, q);
                *d = *e;
            }
            (to, from) => *to = from.clone(),
        }
        state.last_approach = self.last_approach;
        state.landed = self.smooth.as_ref().map(|s| s.landed);
        state.law.clone_from(self.law());
    }

    /// Goes back to `state`, saved from this solver (or one built the same way). A state of
    /// another grid shape or another law (another kind, or the same kind with another
    /// parameter; a custom law restores only into a solver of the same curve) is refused, and
    /// so is any state on a viscoelastic solver (the state holds no arms).
    pub fn restore_state(&mut self, state: &SolverState) -> Result<(), SolverError> {
        if self.visco.is_some() {
            return Err(SolverError::Refused {
                field: tack_fields::MATERIAL_PRONY,
                reason: "a saved state holds no viscoelastic arms: a viscoelastic solver is not \
                         restored (build a new one and run its path again)",
            });
        }
        let describe = |shape: (usize, usize), (zone, smooth): (bool, bool)| {
            let law = match (zone, smooth) {
                (true, _) => "a cohesive zone",
                (false, true) => "a smooth law",
                (false, false) => "zero range",
            };
            format!("{} × {} grid, {law}", shape.0, shape.1)
        };
        let (mine, theirs) = (
            (
                self.bonded.dim(),
                (self.cohesive.is_some(), self.smooth.is_some()),
            ),
            (
                state.bonded.dim(),
                (state.zone.is_some(), state.landed.is_some()),
            ),
        );
        if mine != theirs {
            return Err(SolverError::StateMismatch {
                state: describe(theirs.0, theirs.1),
                solver: describe(mine.0, mine.1),
            });
        }
        if state.law != *self.law() {
            let named = |law: &AdhesionLaw| {
                let (field, value) = law.parameter();
                format!("the law {} with {field} = {value}", law.name())
            };
            return Err(SolverError::StateMismatch {
                state: named(&state.law),
                solver: named(self.law()),
            });
        }
        self.base.pressure.assign(&state.pressure);
        self.base.gap.assign(&state.gap);
        self.base.work.disp.assign(&state.disp);
        self.bonded.assign(&state.bonded);
        if let (Some(c), Some(z)) = (self.cohesive.as_mut(), state.zone.as_ref()) {
            c.zone.assign(z);
        }
        self.history.clone_from(&state.history);
        self.last_approach = state.last_approach;
        if let (Some(s), Some(landed)) = (self.smooth.as_mut(), state.landed) {
            s.landed = landed;
        }
        Ok(())
    }
}
