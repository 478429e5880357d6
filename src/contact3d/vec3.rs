//! 3-vectors of scalars (plain or dual) and the few operations the 3D kernel needs, on the
//! stack.

pub use crate::contact::scalar::Scalar;

/// 3D vector of scalars.
pub type V3<S> = [S; 3];

pub fn add<S: Scalar>(a: V3<S>, b: V3<S>) -> V3<S> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn sub<S: Scalar>(a: V3<S>, b: V3<S>) -> V3<S> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn scale<S: Scalar>(a: V3<S>, s: S) -> V3<S> {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn dot<S: Scalar>(a: V3<S>, b: V3<S>) -> S {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross<S: Scalar>(a: V3<S>, b: V3<S>) -> V3<S> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm<S: Scalar>(a: V3<S>) -> S {
    dot(a, a).sqrt()
}
/// `Σ c_i v_i` of two vectors (a vector from its components in a basis).
pub fn combine<S: Scalar>(c: [S; 2], v: [V3<S>; 2]) -> V3<S> {
    add(scale(v[0], c[0]), scale(v[1], c[1]))
}
pub fn lift<S: Scalar>(a: [f64; 3]) -> V3<S> {
    [S::from(a[0]), S::from(a[1]), S::from(a[2])]
}
pub fn re<S: Scalar>(a: V3<S>) -> [f64; 3] {
    [a[0].re(), a[1].re(), a[2].re()]
}
