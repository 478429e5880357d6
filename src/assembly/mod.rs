//! Global assembly: DOF numbering (prescribed DOFs eliminated), element and contact
//! contributions scattered into the full residual and the free-DOF sparse tangent.

pub mod pacing;
pub mod skew;

use crate::contact::system::{Config, ContactSystem};
use crate::contact3d::system::SurfaceConfig;
use crate::element::material::Material;
use crate::element::quad::ElementError;
use crate::linalg::aggregation::MeshNodes;
use crate::linalg::chooser::LinearSolve;
use crate::linalg::factorization::LinearError;
use crate::linalg::sparse::SparseMatrix;
use crate::model::dim::Filled;
use crate::model::{Dim, Model, Plane};
use crate::team::Team;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Where the time of the Newton iterations went (accumulated over a run).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// Element kernels and their scatter (residual, and tangent when asked).
    pub elements: Duration,
    /// Contact pairing, contact kernels and their scatter.
    pub contact: Duration,
    /// Numeric LU factorisations (and the symbolic ones when the pattern changed).
    pub factorization: Duration,
    /// Forward and back substitution.
    pub solve: Duration,
    pub assemblies: usize,
    /// Assemblies that computed the tangent as well.
    pub tangent_assemblies: usize,
    /// Assemblies made without the tangent because Newton expected the iterate to converge
    /// (`solver::newton`), and those of them whose iterate did not, so that it was
    /// assembled again with the tangent.
    pub tangents_skipped: usize,
    pub tangents_missed: usize,
    /// Corrections at which points rested at the normal kink and the open correction drove
    /// some of them in, so that the resting side was tried (`solver::newton`'s choice of the
    /// kink's side), and those at which it was taken.
    pub kink_trials: usize,
    pub resting_corrections: usize,
    pub factorizations: usize,
    /// Threads the run could use for its element kernels (the calling one included), and
    /// the assemblies whose kernels ran on them (the others ran on the calling thread alone,
    /// which the measurements found faster then: [`pacing`]).
    pub threads: usize,
    pub team_assemblies: usize,
}

const NONE: u32 = u32::MAX;

/// Weight of a contact point's `Σ_j |K_ij| |x_j|` in the summed absolute contributions
/// (`r_abs`), so that [`Assembler::roundoff`]'s `1e-13 ‖r_abs‖` is `≈ 10 ε_mach Σ_j |K_ij| |x_j|`:
/// the round-off of a penalty force computed from current positions. With `ε_N = 10⁶ E` on
/// coordinates of order one it is `≈ 10⁻⁹ E`, which the criterion `1e-9 F_ref` cannot go below.
const CONTACT_ROUNDOFF: f64 = 10.0 * f64::EPSILON / 1e-13;

/// Map from global DOFs (`D node + component`) to free equations.
#[derive(Debug, Clone)]
pub struct DofMap {
    /// Equation of each DOF, or `None` when prescribed.
    pub eq: Vec<Option<usize>>,
    pub n_free: usize,
    /// Prescribed DOFs in the order of [`Model::prescribed`], then the two DOFs of each
    /// skew-supported node ([`Model::skew`]; free equations, but their residual along the
    /// support is a reaction, so sums of reactions include them).
    pub prescribed: Vec<usize>,
    /// Per DOF: in [`Self::prescribed`] (fixed, or of a skew-supported node).
    held: Vec<bool>,
}

impl DofMap {
    pub fn new<S: Dim>(model: &Model<S>) -> Self {
        let n = model.dof_count();
        let mut fixed = vec![false; n];
        for p in &model.prescribed {
            fixed[p.dof] = true;
        }
        let mut eq = vec![None; n];
        let mut k = 0;
        for d in 0..n {
            if !fixed[d] {
                eq[d] = Some(k);
                k += 1;
            }
        }
        let skew = model.skew.iter().flat_map(|s| [2 * s.node, 2 * s.node + 1]);
        let prescribed: Vec<usize> = model.prescribed.iter().map(|p| p.dof).chain(skew).collect();
        let mut held = vec![false; n];
        prescribed.iter().for_each(|&d| held[d] = true);
        DofMap {
            eq,
            n_free: k,
            prescribed,
            held,
        }
    }

    /// Whether DOF `d` carries a reaction: prescribed, or of a skew-supported node.
    pub fn is_prescribed(&self, d: usize) -> bool {
        self.held[d]
    }
}

/// `100 ε_mach √Σ_e (E_e h_e w_e)²`, `E_e` Young's modulus, `h_e` the longest edge, `w_e`
/// the measure of the element's forces beyond plane strain: 1 in plane strain and 3D, the
/// thickness in plane stress, `2π R_e` (`R_e` the largest nodal radius) in the axisymmetric
/// setting ([`Dim::force_measure`]).
fn material_floor<S: Dim>(model: &Model<S>) -> f64 {
    let mut sum = 0.0;
    for el in &model.elements {
        let body = &model.bodies[el.body];
        let (Material::SaintVenantKirchhoff { lambda, mu } | Material::NeoHookean { lambda, mu }) = body.material;
        let young = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
        let x: Vec<S::Point> = el.nodes.as_ref().iter().map(|&n| model.nodes[n]).collect();
        let h = S::longest_edge(&x);
        let w = S::force_measure(&body.kinematics, &x);
        sum += (young * h * w).powi(2);
    }
    100.0 * f64::EPSILON * sum.sqrt()
}

/// An element could not be evaluated.
#[derive(Debug, Clone, thiserror::Error)]
#[error("element {element}: {source}")]
pub struct AssemblyError {
    pub element: usize,
    #[source]
    pub source: ElementError,
}

/// Owns the sparse tangent, its linear solves and the scatter maps, for a model of
/// dimension `S` (the element kernels and their local arrays are the dimension's).
pub struct Assembler<S: Dim = Plane> {
    pub dofs: DofMap,
    pub matrix: SparseMatrix,
    /// The factorisations of the tangent (chosen by the `linear_solver` setting).
    pub linear: LinearSolve,
    /// Value index of each element-matrix entry (row-major, `8×8` in 2D, `24×24` in 3D),
    /// `NONE` where prescribed.
    elem_slots: Vec<S::Slots>,
    /// Full residual `f_int + f_contact − f_ext` over all DOFs (reactions at prescribed DOFs).
    pub r_full: Vec<f64>,
    /// Sum of the absolute element and contact contributions per DOF (round-off scale).
    r_abs: Vec<f64>,
    /// The residual of the contact force unknowns minus that of the penalty forces, per
    /// DOF (zero but at contact nodes; see [`Self::merit`]).
    r_forces: Vec<f64>,
    /// Round-off level of the internal forces from the materials: `100 ε_mach √Σ (E_e h_e)²`
    /// (`F = I + ∇u` loses the digits of a small strain below `ε_mach`, so an element's force
    /// is resolved to about `ε_mach E h` per unit thickness whatever its deformation).
    material_floor: f64,
    /// Stored energy of the elements at the last assembly.
    pub energy: f64,
    missing: Vec<(usize, usize)>,
    /// Time spent in assembly (the factorisation times are the matrix's).
    pub timings: Timings,
    /// Reference geometry of each element (computed once; an invalid one fails assembly).
    geometry: Vec<Result<S::Geometry, ElementError>>,
    /// The team that shares the element kernels with the calling thread (`None`: one
    /// thread), and the measured choice of whether it pays ([`pacing`]).
    team: Option<Arc<Team>>,
    pub pacing: pacing::Pacing,
    /// Per-element outputs of one block of the team's path (allocated once).
    block: Vec<ElementOut<S>>,
    /// The skew supports, held in their nodes' local frames ([`skew`]).
    pub skew: skew::Skew,
}

/// Models with at least this many elements may share their element kernels with a team of
/// threads (the run's thread budget); whether an assembly does is measured ([`pacing`]).
/// Below it one assembly takes a few microseconds and waking a thread costs as much.
pub const TEAM_ELEMENTS_FROM: usize = 64;

/// Elements per block of the team's path (the per-element buffers of one block: 4096 × 584
/// bytes), whose outputs are scattered sequentially in element order after the kernels:
/// the sums are the sequential ones, bit for bit.
const BLOCK: usize = 4096;

/// Elements per piece of work a thread claims (≈ 20 µs of kernels: a worker that the
/// operating system stops inside a piece delays the assembly by no more than that piece).
const PIECE: usize = 32;

/// A slice whose disjoint ranges are handed to the team's threads.
struct SharedMut<T> {
    ptr: *mut T,
    len: usize,
}

// SAFETY: only used through `range`, whose callers hand out disjoint ranges (one piece each).
unsafe impl<T: Send> Sync for SharedMut<T> {}

impl<T> SharedMut<T> {
    fn new(s: &mut [T]) -> Self {
        SharedMut {
            ptr: s.as_mut_ptr(),
            len: s.len(),
        }
    }

    /// # Safety
    /// No two live references to overlapping ranges may exist (each piece index is claimed
    /// by one thread exactly once, and pieces cover disjoint ranges).
    #[allow(clippy::mut_from_ref)]
    unsafe fn range(&self, r: std::ops::Range<usize>) -> &mut [T] {
        assert!(r.start <= r.end && r.end <= self.len);
        // SAFETY: in bounds (checked above); exclusive by the caller's contract
        unsafe { std::slice::from_raw_parts_mut(self.ptr.add(r.start), r.end - r.start) }
    }
}

/// One element's kernel output: residual, tangent, energy, or the failure.
#[derive(Clone, Copy)]
struct ElementOut<S: Dim> {
    re: S::Re,
    ke: S::Ke,
    energy: Result<f64, ElementError>,
}

impl<S: Dim> Default for ElementOut<S> {
    fn default() -> Self {
        ElementOut {
            re: S::Re::filled(0.0),
            ke: S::Ke::filled(0.0),
            energy: Ok(0.0),
        }
    }
}

/// The equations of an element's DOFs (`D` per node, in node order).
fn element_eqs<S: Dim>(dofs: &DofMap, nodes: &S::Cell) -> Vec<Option<usize>> {
    (nodes.as_ref().iter())
        .flat_map(|&n| (0..S::D).map(move |c| dofs.eq[S::D * n + c]))
        .collect()
}

impl<S: Dim> Assembler<S> {
    pub fn new(model: &Model<S>) -> Self {
        let dofs = DofMap::new(model);
        let mut groups = model
            .elements
            .iter()
            .map(|el| element_eqs::<S>(&dofs, &el.nodes).iter().flatten().copied().collect());
        let matrix = SparseMatrix::new(dofs.n_free, &mut groups);
        let skew = skew::Skew::new(model.plane(), &dofs.eq, dofs.n_free);
        let mut linear = LinearSolve::default();
        if S::D == 2 {
            let plane = model.plane();
            // a skew node's equations are in its local frame: not in the near-null space
            let turned: std::collections::HashSet<usize> = skew.dofs.iter().map(|s| s.node).collect();
            linear.set_nodes(MeshNodes::Plane(
                (plane.nodes.iter().enumerate())
                    .map(|(i, x)| match turned.contains(&i) {
                        true => ([None, None], *x),
                        false => ([dofs.eq[2 * i], dofs.eq[2 * i + 1]], *x),
                    })
                    .collect(),
            ));
        } else if let Some(solid) = S::solid(model) {
            linear.set_nodes(MeshNodes::Solid(
                (solid.nodes.iter().enumerate())
                    .map(|(i, x)| ([dofs.eq[3 * i], dofs.eq[3 * i + 1], dofs.eq[3 * i + 2]], *x))
                    .collect(),
            ));
        }
        let mut a = Assembler {
            dofs,
            matrix,
            linear,
            elem_slots: Vec::new(),
            r_full: vec![0.0; model.dof_count()],
            r_abs: vec![0.0; model.dof_count()],
            r_forces: vec![0.0; model.dof_count()],
            material_floor: material_floor(model),
            energy: 0.0,
            missing: Vec::new(),
            timings: Timings::default(),
            geometry: model
                .elements
                .iter()
                .map(|el| {
                    let x: Vec<S::Point> = el.nodes.as_ref().iter().map(|&n| model.nodes[n]).collect();
                    S::geometry(&model.bodies[el.body], &x)
                })
                .collect(),
            team: None,
            pacing: pacing::Pacing::default(),
            block: Vec::new(),
            skew,
        };
        a.build_slots(model);
        a
    }

    /// Share the element kernels among `threads` threads (the calling one included) on
    /// models of at least [`TEAM_ELEMENTS_FROM`] elements; 1 keeps them on the calling
    /// thread. Every choice gives the same bits (the scatter is sequential in element order).
    pub fn set_threads(&mut self, threads: usize, elements: usize) {
        let team = (threads > 1 && elements >= TEAM_ELEMENTS_FROM).then(|| Team::new(threads));
        self.team = team.filter(|t| t.threads() > 1).map(Arc::new);
        // the iterative solver's products and smoothing go to the same (sleeping) team
        self.linear.set_team(self.team.clone());
        self.block = match self.team {
            Some(_) => vec![ElementOut::default(); elements.min(BLOCK)],
            None => Vec::new(),
        };
        self.pacing = pacing::Pacing::default();
    }

    /// Threads that may evaluate the element kernels (the calling one included).
    pub fn threads(&self) -> usize {
        self.team.as_ref().map_or(1, |t| t.threads())
    }

    /// Add one element's residual and tangent into the global arrays.
    #[inline]
    fn scatter_element(&mut self, ie: usize, nodes: &S::Cell, re: &S::Re, ke: Option<&S::Ke>) {
        let re = re.as_ref();
        for (i, &n) in nodes.as_ref().iter().enumerate() {
            for c in 0..S::D {
                self.r_full[S::D * n + c] += re[S::D * i + c];
                self.r_abs[S::D * n + c] += re[S::D * i + c].abs();
            }
        }
        if let Some(ke) = ke {
            for (s, v) in self.elem_slots[ie].as_ref().iter().zip(ke.as_ref().iter()) {
                if *s != NONE {
                    self.matrix.values[*s as usize] += v;
                }
            }
        }
    }

    fn elements_sequential(
        &mut self,
        model: &Model<S>,
        u: &[f64],
        alphas: &mut [S::Alpha],
        with_tangent: bool,
    ) -> Result<(), AssemblyError> {
        let mut re = S::Re::filled(0.0);
        let mut ke = S::Ke::filled(0.0);
        for (ie, el) in model.elements.iter().enumerate() {
            let k = with_tangent.then_some(&mut ke);
            self.energy += element_kernel(model, el, &self.geometry[ie], u, &mut alphas[ie], &mut re, k)
                .map_err(|source| AssemblyError { element: ie, source })?;
            self.scatter_element(ie, &el.nodes, &re, with_tangent.then_some(&ke));
        }
        Ok(())
    }

    /// Blocks of [`BLOCK`] elements: kernels on the team into per-element buffers (each
    /// element owns its buffer and its `alphas` entry; threads claim pieces of [`PIECE`]
    /// elements), then the sequential scatter in element order, so residual, tangent and
    /// energy are summed exactly as in [`Self::elements_sequential`]. The first failing
    /// element (in element order) is reported, as sequentially; the `alphas` of the later
    /// elements of its block have been updated as well (a failed assembly leaves the trial
    /// state dirty either way).
    fn elements_team(
        &mut self,
        model: &Model<S>,
        u: &[f64],
        alphas: &mut [S::Alpha],
        with_tangent: bool,
    ) -> Result<(), AssemblyError> {
        let Some(team) = self.team.take() else {
            return self.elements_sequential(model, u, alphas, with_tangent);
        };
        let mut block = std::mem::take(&mut self.block);
        let n = model.elements.len();
        let mut result = Ok(());
        for first in (0..n).step_by(BLOCK) {
            let last = (first + BLOCK).min(n);
            let out = SharedMut::new(&mut block[..last - first]);
            let al = SharedMut::new(&mut alphas[first..last]);
            let geometry = &self.geometry;
            team.run((last - first).div_ceil(PIECE), &|k| {
                let range = k * PIECE..((k + 1) * PIECE).min(last - first);
                // SAFETY: piece k is claimed once and the pieces' ranges are disjoint
                let (out, al) = unsafe { (out.range(range.clone()), al.range(range.clone())) };
                for (j, (o, alpha)) in out.iter_mut().zip(al.iter_mut()).enumerate() {
                    let ie = first + range.start + j;
                    let kk = with_tangent.then_some(&mut o.ke);
                    o.energy = element_kernel(model, &model.elements[ie], &geometry[ie], u, alpha, &mut o.re, kk);
                }
            });
            result = self.scatter_outputs(model, first, &block[..last - first], with_tangent);
            if result.is_err() {
                break;
            }
        }
        self.block = block;
        self.team = Some(team);
        result
    }

    /// The element kernels on the calling thread or the team, whichever the measurements
    /// say is faster now ([`pacing`]).
    fn elements(
        &mut self,
        model: &Model<S>,
        u: &[f64],
        alphas: &mut [S::Alpha],
        with_tangent: bool,
    ) -> Result<(), AssemblyError> {
        let mode = match self.team {
            Some(_) => self.pacing.choose(with_tangent),
            None => pacing::Mode::Alone,
        };
        let started = Instant::now();
        match mode {
            pacing::Mode::Alone => self.elements_sequential(model, u, alphas, with_tangent)?,
            pacing::Mode::Team => self.elements_team(model, u, alphas, with_tangent)?,
        }
        if self.team.is_some() {
            self.pacing.record(with_tangent, mode, started.elapsed());
        }
        Ok(())
    }

    /// Sum the kernel outputs `out` of the elements from `first` on, in element order (the
    /// sequential path's order): energy, residual and (with the tangent) matrix values.
    /// Stops at the first failed element and reports it.
    fn scatter_outputs(
        &mut self,
        model: &Model<S>,
        first: usize,
        out: &[ElementOut<S>],
        with_tangent: bool,
    ) -> Result<(), AssemblyError> {
        for (k, o) in out.iter().enumerate() {
            let ie = first + k;
            self.energy += o.energy.map_err(|source| AssemblyError { element: ie, source })?;
            self.scatter_element(ie, &model.elements[ie].nodes, &o.re, with_tangent.then_some(&o.ke));
        }
        Ok(())
    }

    fn build_slots(&mut self, model: &Model<S>) {
        self.elem_slots = model
            .elements
            .iter()
            .map(|el| {
                let e = element_eqs::<S>(&self.dofs, &el.nodes);
                let n = e.len();
                let mut s = S::Slots::filled(NONE);
                for i in 0..n {
                    for j in 0..n {
                        if let (Some(r), Some(c)) = (e[i], e[j]) {
                            s.as_mut()[n * i + j] = self.matrix.index(r, c).expect("element pattern") as u32;
                        }
                    }
                }
                s
            })
            .collect();
    }

    /// Assemble the residual (and the tangent if `with_tangent`) at displacement `u`, time `t`.
    /// `alphas` (enhanced-strain parameters, [`Dim::ALPHAS`] per element) are updated in place.
    pub fn assemble(
        &mut self,
        model: &Model<S>,
        u: &[f64],
        t: f64,
        alphas: &mut [f64],
        contact: &mut ContactSystem,
        with_tangent: bool,
    ) -> Result<(), AssemblyError> {
        self.timings.assemblies += 1;
        self.timings.tangent_assemblies += usize::from(with_tangent);
        loop {
            let started = Instant::now();
            self.r_full.fill(0.0);
            self.r_abs.fill(0.0);
            self.r_forces.fill(0.0);
            self.matrix.clear_values();
            self.energy = 0.0;
            self.elements(model, u, S::alphas_mut(alphas), with_tangent)?;
            self.missing.clear();
            let elements_done = Instant::now();
            self.timings.elements += elements_done - started;
            let cfg = Config {
                model: model.plane(),
                u,
                t,
            };
            let (r_full, r_abs, r_forces, matrix, missing, dofs) = (
                &mut self.r_full,
                &mut self.r_abs,
                &mut self.r_forces,
                &mut self.matrix,
                &mut self.missing,
                &self.dofs,
            );
            let mut sink = |dof_ids: &[usize], r: &[f64], r_eq: &[f64], k: &[f64], positions: &[f64]| {
                let nd = dof_ids.len();
                let dof = |i: usize| dof_ids[i];
                for i in 0..nd {
                    r_full[dof(i)] += r[i];
                    r_forces[dof(i)] += r_eq[i] - r[i];
                    // a penalty force is ε times a difference of positions, each known to
                    // ε_mach |x| (`positions`: the point's coordinates about its own origin,
                    // the rigid geometry's included): its round-off is ε_mach Σ_j |K_ij| |x_j|
                    // (the residual criterion's floor, `roundoff`, is 1e-13 times this sum)
                    let k_x: f64 = (0..nd).map(|j| k[nd * i + j].abs() * positions[j]).sum();
                    r_abs[dof(i)] += r_eq[i].abs() + CONTACT_ROUNDOFF * k_x;
                }
                if !with_tangent {
                    return;
                }
                for i in 0..nd {
                    let Some(ri) = dofs.eq[dof(i)] else { continue };
                    for j in 0..nd {
                        let Some(cj) = dofs.eq[dof(j)] else { continue };
                        match matrix.index(ri, cj) {
                            Some(s) => matrix.add_to(s, k[nd * i + j]),
                            None => missing.push((ri, cj)),
                        }
                    }
                }
            };
            contact.evaluate(&cfg, &mut sink);
            if let Some(solid) = S::solid(model) {
                let cfg = SurfaceConfig { model: solid, u, t };
                contact.surface.evaluate(&cfg, &mut sink);
            }
            self.timings.contact += elements_done.elapsed();
            if self.missing.is_empty() {
                break;
            }
            // contact coupled new DOFs: grow the pattern (new symbolic analysis) and redo
            let missing = std::mem::take(&mut self.missing);
            self.matrix.extend(&missing);
            self.build_slots(model);
        }
        for l in &model.loads {
            let f = l.ramp.at(t);
            self.r_full[l.dof] -= f;
            self.r_abs[l.dof] += f.abs();
        }
        if !self.skew.is_empty() {
            self.skew.update_gaps(model.plane(), u, t);
            if with_tangent {
                self.skew.transform(&mut self.matrix);
            }
        }
        Ok(())
    }

    /// Solve `K x = b` in place with the assembled tangent (`b` and `x` in global components;
    /// at skew-supported nodes the solve runs in their local frames, [`skew`]).
    pub fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
        self.skew.to_local(b);
        self.linear.solve(&self.matrix, b)?;
        self.skew.to_global(b);
        Ok(())
    }

    /// Return the matrix to the elements' pattern when the entries contact added to it were
    /// not written since the last call (see [`SparseMatrix::shrink_unused_extension`]); called
    /// once per increment. Returns whether the pattern changed.
    pub fn shrink_unused_contact_pattern(&mut self, model: &Model<S>) -> bool {
        let changed = self.matrix.shrink_unused_extension(self.linear.banded());
        if changed {
            self.build_slots(model);
        }
        changed
    }

    /// Round-off level of the free residual: the larger of `1e-13 ‖Σ|r_e|‖` over the free
    /// DOFs (the norm of the summed absolute contributions) and the materials' floor (see
    /// `material_floor`); a residual below it is noise.
    pub fn roundoff(&self) -> f64 {
        let s: f64 = self
            .dofs
            .eq
            .iter()
            .zip(&self.r_abs)
            .filter(|(e, _)| e.is_some())
            .map(|(_, a)| a * a)
            .sum();
        (1e-13 * s.sqrt()).max(self.material_floor)
    }

    /// The assembly timings with the matrix's factorisation and solve times.
    pub fn timings(&self) -> Timings {
        Timings {
            factorization: self.linear.times.factor_time,
            solve: self.linear.times.solve_time,
            factorizations: self.linear.times.factorizations,
            threads: self.threads(),
            team_assemblies: self.pacing.team,
            ..self.timings
        }
    }

    /// Hold the hourglass modes of the `q4-eas-safe` (3D: `hex8-eas-safe`) elements for the
    /// next increment, from the converged displacements `u` (see
    /// [`crate::element::quad::hourglass_holds`], [`crate::element::hex8::hex8_hourglass_holds`]).
    pub fn update_hourglass_holds(&mut self, model: &Model<S>, u: &[f64]) {
        for (el, geo) in model.elements.iter().zip(self.geometry.iter_mut()) {
            let body = &model.bodies[el.body];
            let Ok(geo) = geo else { continue };
            if !S::holds_hourglass(&body.kind) {
                continue;
            }
            S::hold_hourglass(body, geo, &el.nodes, u);
        }
    }

    /// The tangent of element `ie` at displacements `u` (row-major, `8×8` in 2D), from the
    /// enhanced parameters `alpha` (a copy is iterated on; the state is not changed).
    pub fn element_tangent(
        &self,
        model: &Model<S>,
        ie: usize,
        u: &[f64],
        alpha: &S::Alpha,
        k: &mut S::Ke,
    ) -> Result<(), AssemblyError> {
        let (mut a, mut r) = (*alpha, S::Re::filled(0.0));
        element_kernel(
            model,
            &model.elements[ie],
            &self.geometry[ie],
            u,
            &mut a,
            &mut r,
            Some(k),
        )
        .map(|_| ())
        .map_err(|source| AssemblyError { element: ie, source })
    }

    /// Newton's merit function at the last assembly: `‖R(u, N, T)‖² + Σ C²`, the squared
    /// residual of the mixed system — equilibrium with the contact force unknowns at the
    /// free DOFs, and the complementarity residuals of every contact point (`contact`, as
    /// evaluated by that assembly; see [`crate::contact::decision`]).
    /// At a skew-supported node the pair of equilibrium residuals is that of
    /// [`skew::Skew::residual`] (constraint along `n`, equilibrium along `t`).
    pub fn merit(&self, contact: &ContactSystem) -> f64 {
        let eq: f64 = (self.dofs.eq.iter().zip(self.r_full.iter().zip(&self.r_forces)))
            .enumerate()
            .filter(|(d, (e, _))| e.is_some() && !self.skew.turns(*d))
            .map(|(_, (_, (r, f)))| (r + f) * (r + f))
            .sum();
        let skew: f64 = (self.skew.dofs.iter().enumerate())
            .map(|(k, s)| {
                let [x, y] = [2 * s.node, 2 * s.node + 1].map(|d| self.r_full[d] + self.r_forces[d]);
                let f = self.skew.residual(k, [x, y]);
                f[0] * f[0] + f[1] * f[1]
            })
            .sum();
        eq + skew + contact.complementarity2()
    }

    /// Residual restricted to the free equations (at a skew-supported node: the constraint
    /// residual along its direction, equilibrium across it, [`skew::Skew::residual`]).
    pub fn free_residual(&self, out: &mut [f64]) {
        for (d, e) in self.dofs.eq.iter().enumerate() {
            if let Some(e) = e {
                out[*e] = self.r_full[d];
            }
        }
        for (k, s) in self.skew.dofs.iter().enumerate() {
            let f = self
                .skew
                .residual(k, [self.r_full[2 * s.node], self.r_full[2 * s.node + 1]]);
            out[s.eqs[0]] = f[0];
            out[s.eqs[1]] = f[1];
        }
    }
}

/// One element's kernel on its nodes' displacements (the element's reference geometry, or
/// why it has none, computed once by the assembler).
#[inline]
fn element_kernel<S: Dim>(
    model: &Model<S>,
    el: &crate::model::Element<S>,
    geo: &Result<S::Geometry, ElementError>,
    u: &[f64],
    alpha: &mut S::Alpha,
    re: &mut S::Re,
    ke: Option<&mut S::Ke>,
) -> Result<f64, ElementError> {
    let body = &model.bodies[el.body];
    let geo = geo.as_ref().map_err(|e| *e)?;
    S::kernel(body, geo, &el.nodes, u, alpha, re, ke)
}

#[cfg(test)]
mod tests;
