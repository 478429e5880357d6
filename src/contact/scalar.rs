//! The scalar type contact kernels are written in: `f64` for plain evaluation, or a
//! second-order dual number (num-dual) whose gradient and Hessian give the variations
//! `δζ, δξ` and their linearisations exactly.

use num_dual::DualNum;

/// A real number or a dual number carrying derivatives with respect to the local contact
/// unknowns.
pub trait Scalar: DualNum<f64> + Copy {}
impl<T: DualNum<f64> + Copy> Scalar for T {}

/// 2D vector of scalars.
pub type V2<S> = [S; 2];

pub fn sub<S: Scalar>(a: V2<S>, b: V2<S>) -> V2<S> {
    [a[0] - b[0], a[1] - b[1]]
}
pub fn add<S: Scalar>(a: V2<S>, b: V2<S>) -> V2<S> {
    [a[0] + b[0], a[1] + b[1]]
}
pub fn scale<S: Scalar>(a: V2<S>, s: S) -> V2<S> {
    [a[0] * s, a[1] * s]
}
pub fn dot<S: Scalar>(a: V2<S>, b: V2<S>) -> S {
    a[0] * b[0] + a[1] * b[1]
}
pub fn lift<S: Scalar>(a: [f64; 2]) -> V2<S> {
    [S::from(a[0]), S::from(a[1])]
}
pub fn re<S: Scalar>(a: V2<S>) -> [f64; 2] {
    [a[0].re(), a[1].re()]
}
