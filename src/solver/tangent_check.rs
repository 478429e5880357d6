//! Finite-difference check of the assembled tangent at one iterate: a diagnosis for a Newton
//! iteration that does not converge. Quadratic convergence needs the tangent to be the
//! derivative of the residual; where it is not — a kernel's tangent is wrong, or the residual
//! has a kink or a jump at this iterate (a contact point on the edge of its active set) — the
//! check says which columns, by how much, and whether the residual is smooth there.
//!
//! For each checked free equation `j` (a displacement component of a node) the residual is
//! assembled at `u ± h e_j` with the contact decisions re-made at each (as the solver would),
//! and compared with column `j` of the tangent `K` assembled at `u`:
//!
//! - central difference `d_c = (R(u + h e_j) − R(u − h e_j)) / 2h`, error
//!   `‖K e_j − d_c‖∞ / max(‖K e_j‖∞, ‖d_c‖∞)`;
//! - one-sided differences `d_± = ±(R(u ± h e_j) − R(u)) / h`: when they differ by more than
//!   the tangent error tolerance the residual is not differentiable along `e_j` at `u` (a
//!   *kink*: a point switching state within `±h`), and no tangent can be exact there; so is a
//!   column that disagrees with the central difference but agrees with one of `d_±` (the
//!   tangent of one side of a small kink: a slave point exactly at the joint of two segments
//!   of a C1-smoothed face, whose curvature, and so the tangent, jumps there);
//! - a *jump*: `‖R(u + h e_j) − R(u − h e_j)‖∞` far larger than `‖K e_j‖∞ 2h` — the
//!   residual is discontinuous there (a pairing rule switching a force on or off).
//!
//! `h = 1e-7 L` with `L` the model's size (the diagonal of its bounding box): small against
//! the element size, large against round-off of the coordinates.

use super::state::TrialState;
use crate::assembly::{Assembler, AssemblyError};
use crate::model::{Dim, Model};

/// Relative column error above which a column counts as wrong (well above the `O(h)`
/// truncation and `O(ε/h)` round-off of a central difference at `h = 1e-7 L`).
pub const COLUMN_TOLERANCE: f64 = 1e-4;

/// The check of one column of the tangent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColumnCheck {
    /// Node and component (0: x, 1: y, 2: z) of the column's degree of freedom.
    pub node: usize,
    pub component: usize,
    /// `‖K e_j − d_c‖∞ / max(‖K e_j‖∞, ‖d_c‖∞)`.
    pub error: f64,
    /// One-sided differences disagree: the residual is not smooth along this column here.
    pub kink: bool,
    /// The residual jumps along this column (a discontinuity, not a kink).
    pub jump: bool,
}

/// Result of a tangent check at one iterate.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TangentCheck {
    /// Columns checked (all free equations of a small model, otherwise those of the nodes
    /// asked for).
    pub columns: usize,
    /// Columns whose error exceeds [`COLUMN_TOLERANCE`] on a smooth residual (a tangent that
    /// is wrong), worst first.
    pub wrong: Vec<ColumnCheck>,
    /// Columns along which the residual has a kink or a jump at this iterate, worst first.
    pub non_smooth: Vec<ColumnCheck>,
    /// Largest error over the smooth columns.
    pub max_error: f64,
}

impl TangentCheck {
    /// One line for the run's log.
    pub fn summary(&self) -> String {
        let list = |v: &[ColumnCheck]| {
            v.iter()
                .take(6)
                .map(|c| {
                    let what = if c.jump { " jump" } else { "" };
                    format!(
                        "node {} {} ({:.1e}{what})",
                        c.node,
                        ["x", "y", "z"][c.component],
                        c.error
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut s = format!(
            "tangent check (finite differences, {} columns): largest error on smooth columns {:.1e}",
            self.columns, self.max_error
        );
        if self.wrong.is_empty() {
            s.push_str("; no wrong column");
        } else {
            s.push_str(&format!("; {} wrong: {}", self.wrong.len(), list(&self.wrong)));
        }
        if !self.non_smooth.is_empty() {
            s.push_str(&format!(
                "; the residual is not smooth along {} columns (contact decisions switch there, or a point sits on a joint of a smoothed face): {}",
                self.non_smooth.len(),
                list(&self.non_smooth)
            ));
        }
        s
    }
}

/// Largest model whose every column is checked; larger ones check the nodes given.
pub const ALL_COLUMNS_UP_TO: usize = 4000;

/// Check the tangent at `state` (time `t`) column by column. `nodes`: the nodes whose
/// columns to check when the model has more than [`ALL_COLUMNS_UP_TO`] free equations.
/// `state` is left as it was; the assembler holds the residual and tangent at `state`.
pub fn check_tangent<S: Dim>(
    model: &Model<S>,
    asm: &mut Assembler<S>,
    state: &TrialState,
    t: f64,
    nodes: &[usize],
) -> Result<TangentCheck, AssemblyError> {
    let n = asm.dofs.n_free;
    let dofs: Vec<usize> = if n <= ALL_COLUMNS_UP_TO {
        (0..model.dof_count()).filter(|&d| asm.dofs.eq[d].is_some()).collect()
    } else {
        nodes
            .iter()
            .flat_map(|&nd| (0..S::D).map(move |c| S::D * nd + c))
            .filter(|&d| asm.dofs.eq[d].is_some())
            .collect()
    };
    let h = 1e-7 * model.size();
    let residual_at = |asm: &mut Assembler<S>, u: &[f64]| -> Result<Vec<f64>, AssemblyError> {
        let mut trial = state.clone();
        asm.assemble(model, u, t, &mut trial.alphas, &mut trial.contact, false)?;
        let mut r = vec![0.0; n];
        asm.free_residual(&mut r);
        Ok(r)
    };
    let r0 = residual_at(asm, &state.u)?;
    let mut out = TangentCheck {
        columns: dofs.len(),
        ..TangentCheck::default()
    };
    let mut columns = Vec::with_capacity(dofs.len());
    let mut u = state.u.clone();
    for &d in &dofs {
        u[d] = state.u[d] + h;
        let rp = residual_at(asm, &u)?;
        u[d] = state.u[d] - h;
        let rm = residual_at(asm, &u)?;
        u[d] = state.u[d];
        columns.push((d, rp, rm));
    }
    // the tangent at the iterate itself, last: the assembler is left holding it
    let mut at = state.clone();
    asm.assemble(model, &state.u, t, &mut at.alphas, &mut at.contact, true)?;
    for (d, rp, rm) in columns {
        let j = asm.dofs.eq[d].expect("free");
        let k: Vec<f64> = (0..n)
            .map(|i| asm.matrix.index(i, j).map_or(0.0, |s| asm.matrix.values[s]))
            .collect();
        out.record(compare((d, S::D), &k, &r0, &rp, &rm, h));
    }
    let worst_first = |v: &mut Vec<ColumnCheck>| v.sort_by(|a, b| b.error.total_cmp(&a.error));
    worst_first(&mut out.wrong);
    worst_first(&mut out.non_smooth);
    Ok(out)
}

impl TangentCheck {
    fn record(&mut self, c: ColumnCheck) {
        if c.kink || c.jump {
            self.non_smooth.push(c);
        } else {
            self.max_error = self.max_error.max(c.error);
            if c.error > COLUMN_TOLERANCE {
                self.wrong.push(c);
            }
        }
    }
}

/// Compare column `k` of the tangent with the differences of the residuals `r0` (at `u`),
/// `rp`, `rm` (at `u ± h e_d`).
/// Column `d` (a DOF of a model with `dim` components per node) of the tangent `k` against
/// the residuals at `u` (`r0`) and `u ± h e_d` (`rp`, `rm`).
fn compare((d, dim): (usize, usize), k: &[f64], r0: &[f64], rp: &[f64], rm: &[f64], h: f64) -> ColumnCheck {
    let inf = |f: &dyn Fn(usize) -> f64| (0..k.len()).map(f).fold(0.0f64, |m, v| m.max(v.abs()));
    let central = |i: usize| (rp[i] - rm[i]) / (2.0 * h);
    let scale = inf(&|i| k[i]).max(inf(&central)).max(f64::MIN_POSITIVE);
    let error = inf(&|i| k[i] - central(i)) / scale;
    let sided = inf(&|i| (rp[i] - r0[i]) / h - (r0[i] - rm[i]) / h) / scale;
    let jump = inf(&|i| rp[i] - rm[i]) > 1e3 * 2.0 * h * inf(&|i| k[i]).max(f64::MIN_POSITIVE);
    let one_side = |side: &dyn Fn(usize) -> f64| inf(&|i| k[i] - side(i)) / scale <= COLUMN_TOLERANCE;
    let from_one_side =
        error > COLUMN_TOLERANCE && (one_side(&|i| (rp[i] - r0[i]) / h) || one_side(&|i| (r0[i] - rm[i]) / h));
    ColumnCheck {
        node: d / dim,
        component: d % dim,
        error,
        kink: sided > 1e2 * COLUMN_TOLERANCE || from_one_side,
        jump,
    }
}

/// The nodes a list of contact points couples at the current iterate: slave nodes and the
/// nodes of the deformable master segments (3D: facets) they are paired with (the columns
/// worth checking in a large model).
pub fn nodes_of_points(
    model: &Model,
    solid: Option<&Model<crate::model::Solid>>,
    contact: &crate::contact::system::ContactSystem,
    points: &[crate::record::ChangingPoint],
) -> Vec<usize> {
    use crate::model::{Master, Slave};
    let mut nodes = Vec::new();
    for p in points {
        if p.surface {
            if let (Some(solid), Some(facet)) = (solid, contact.surface.facet(p.pair, p.slave)) {
                let pair = &solid.surface_contacts[p.pair];
                nodes.push(pair.slaves[p.slave]);
                if let crate::model::SurfaceMaster::Facets { facets, .. } = &pair.master {
                    nodes.extend(facets[facet]);
                }
            }
            continue;
        }
        let pair = &model.contacts[p.pair];
        if let Slave::Node(n) = pair.slaves[p.slave] {
            nodes.push(n);
        }
        if let (Master::Face { segments, .. }, Some(s)) = (&pair.master, contact.current[p.pair][p.slave].segment) {
            nodes.extend(segments[s]);
        }
    }
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Residual `r(x) = a x` for `x < 0`, `b x` for `x ≥ 0`, checked at `x = 0` with `h = 1e-3`.
    fn kinked(a: f64, b: f64, k: f64) -> ColumnCheck {
        let h = 1e-3;
        compare((0, 2), &[k], &[0.0], &[b * h], &[-a * h], h)
    }

    /// A column is named by its node and component in the model's dimension: DOF 6123 is
    /// node 2041's `x` in 3D (not node 3061's `y`, as a 2D count would say).
    #[test]
    fn a_column_is_named_by_the_models_dimension() {
        let c = compare((6123, 3), &[1.0], &[0.0], &[1e-3], &[-1e-3], 1e-3);
        assert_eq!((c.node, c.component), (2041, 0));
        let check = TangentCheck {
            columns: 1,
            wrong: vec![ColumnCheck { error: 0.5, ..c }],
            ..TangentCheck::default()
        };
        assert!(check.summary().contains("node 2041 x"), "{}", check.summary());
        let c = compare((6125, 3), &[1.0], &[0.0], &[1e-3], &[-1e-3], 1e-3);
        assert_eq!((c.node, c.component), (2041, 2));
        assert_eq!(compare((7, 2), &[1.0], &[0.0], &[1e-3], &[-1e-3], 1e-3).node, 3);
    }

    #[test]
    fn a_right_tangent_is_no_error() {
        let c = kinked(2.0, 2.0, 2.0);
        assert!(c.error < 1e-12 && !c.kink && !c.jump);
    }

    #[test]
    fn a_wrong_tangent_on_a_smooth_residual_is_wrong() {
        let c = kinked(2.0, 2.0, 2.1);
        assert!(c.error > COLUMN_TOLERANCE && !c.kink);
    }

    #[test]
    fn the_tangent_of_one_side_of_a_small_kink_is_not_called_wrong() {
        // slopes 2 and 2.01: the central difference is 2.005, the tangent the right side's
        let c = kinked(2.0, 2.01, 2.01);
        assert!(c.error > COLUMN_TOLERANCE, "{c:?}");
        assert!(c.kink, "{c:?}");
        // a tangent matching neither side is still wrong
        let c = kinked(2.0, 2.01, 2.02);
        assert!(!c.kink, "{c:?}");
    }
}
