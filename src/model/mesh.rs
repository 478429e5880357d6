//! Structured mesh generation and the named node sets and boundary faces it provides.

use std::collections::BTreeMap;

/// Counter-clockwise quadrilateral mesh of a rectangle, with optional geometric grading.
#[derive(Debug, Clone)]
pub struct RectMesh {
    /// Node coordinates, row by row from the bottom (`j`), left to right (`i`).
    pub nodes: Vec<[f64; 2]>,
    /// Quads `[bottom-left, bottom-right, top-right, top-left]` (counter-clockwise).
    pub quads: Vec<[usize; 4]>,
    /// Named node sets: `left`, `right`, `bottom`, `top`, `all`, and the corners
    /// `bottom-left`, `bottom-right`, `top-left`, `top-right`.
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Named boundary faces as chains of segments `[a, b]` that run counter-clockwise
    /// around the body (so the outward normal is the segment direction turned by −90°):
    /// `bottom` runs +x, `right` +y, `top` −x, `left` −y.
    pub faces: BTreeMap<String, Vec<[usize; 2]>>,
}

/// Coordinates of `n` intervals on `[0, len]`; `ratio` is the last interval over the first.
pub fn graded_coords(len: f64, n: usize, ratio: f64) -> Vec<f64> {
    if n == 0 {
        return vec![0.0];
    }
    let q = if n > 1 { ratio.powf(1.0 / (n as f64 - 1.0)) } else { 1.0 };
    let w: Vec<f64> = (0..n).map(|i| q.powi(i as i32)).collect();
    let total: f64 = w.iter().sum();
    let mut c = vec![0.0];
    let mut acc = 0.0;
    for wi in &w {
        acc += wi;
        c.push(len * acc / total);
    }
    c[n] = len;
    c
}

/// How the elements along one axis of a structured mesh are sized (`n` elements on
/// `[0, len]`); each variant's `ratio` compares element sizes, so 1 is uniform.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AxisGrading {
    /// Geometric from the first to the last element: `ratio` = last / first.
    End(f64),
    /// Symmetric about the middle, each element's size `q^k` with `k` its distance in
    /// elements from the nearer end: `ratio` = middle / end (> 1: fine at both ends).
    Both(f64),
    /// Symmetric about the middle, fine there: `ratio` = end / middle (the inverse of
    /// [`AxisGrading::Both`]).
    Centre(f64),
    /// Fine at the interior point `at` (`0 < at < len`), a node there: the elements split
    /// between the two sides in proportion to their lengths (at least one each), each side
    /// geometric towards `at` with `ratio` = element at the end / element at `at`.
    At { ratio: f64, at: f64 },
}

/// Node coordinates (`n + 1`, from 0 to `len`) of `n` elements on `[0, len]` sized by `g`.
pub fn axis_coords(len: f64, n: usize, g: AxisGrading) -> Vec<f64> {
    match g {
        AxisGrading::End(ratio) => graded_coords(len, n, ratio),
        AxisGrading::Both(ratio) => symmetric_coords(len, n, ratio),
        AxisGrading::Centre(ratio) => symmetric_coords(len, n, 1.0 / ratio),
        AxisGrading::At { ratio, at } if n >= 2 && at > 0.0 && at < len => {
            let n1 = ((n as f64 * at / len).round() as usize).clamp(1, n - 1);
            let left = graded_coords(at, n1, 1.0 / ratio);
            let right = graded_coords(len - at, n - n1, ratio);
            let mut c = left;
            c.extend(right[1..].iter().map(|x| at + x));
            c[n] = len;
            c
        }
        AxisGrading::At { .. } => graded_coords(len, n, 1.0),
    }
}

/// Element sizes `∝ q^min(i, n−1−i)` with `q = ratio^(1/m)`, `m = ⌊(n−1)/2⌋`: the middle
/// element(s) `ratio` times the end ones.
fn symmetric_coords(len: f64, n: usize, ratio: f64) -> Vec<f64> {
    let m = n.saturating_sub(1) / 2;
    let q = if m > 0 { ratio.powf(1.0 / m as f64) } else { 1.0 };
    let w: Vec<f64> = (0..n).map(|i| q.powi(i.min(n - 1 - i) as i32)).collect();
    let total: f64 = w.iter().sum();
    let mut c = Vec::with_capacity(n + 1);
    c.push(0.0);
    let mut acc = 0.0;
    for wi in &w {
        acc += wi;
        c.push(len * acc / total);
    }
    c[n] = len;
    c
}

/// Turn `nodes` by `angle_deg` (counter-clockwise) about `about`: `x' = p + Q(θ)(x − p)`.
/// A rotation keeps quads counter-clockwise and faces' orientation.
pub fn rotate(nodes: &mut [[f64; 2]], angle_deg: f64, about: [f64; 2]) {
    let (s, c) = angle_deg.to_radians().sin_cos();
    for x in nodes {
        let (dx, dy) = (x[0] - about[0], x[1] - about[1]);
        *x = [about[0] + c * dx - s * dy, about[1] + s * dx + c * dy];
    }
}

impl RectMesh {
    /// `origin` is the bottom-left corner; `grading = [rx, ry]` is the ratio of last to first
    /// element size along x and y (1 = uniform).
    pub fn new(origin: [f64; 2], size: [f64; 2], elements: [usize; 2], grading: [f64; 2]) -> Self {
        let xs = graded_coords(size[0], elements[0], grading[0]);
        let ys = graded_coords(size[1], elements[1], grading[1]);
        Self::on_grid(origin, &xs, &ys)
    }

    /// The mesh of the grid `origin + (xs[i], ys[j])` (each list increasing from 0, one more
    /// entry than elements).
    pub fn on_grid(origin: [f64; 2], xs: &[f64], ys: &[f64]) -> Self {
        let (nx, ny) = (xs.len() - 1, ys.len() - 1);
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        for y in ys {
            for x in xs {
                nodes.push([origin[0] + x, origin[1] + y]);
            }
        }
        let mut quads = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                quads.push([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let mut node_sets = BTreeMap::new();
        node_sets.insert("left".into(), (0..=ny).map(|j| id(0, j)).collect());
        node_sets.insert("right".into(), (0..=ny).map(|j| id(nx, j)).collect());
        node_sets.insert("bottom".into(), (0..=nx).map(|i| id(i, 0)).collect());
        node_sets.insert("top".into(), (0..=nx).map(|i| id(i, ny)).collect());
        node_sets.insert("all".into(), (0..nodes.len()).collect());
        node_sets.insert("bottom-left".into(), vec![id(0, 0)]);
        node_sets.insert("bottom-right".into(), vec![id(nx, 0)]);
        node_sets.insert("top-left".into(), vec![id(0, ny)]);
        node_sets.insert("top-right".into(), vec![id(nx, ny)]);
        let mut faces = BTreeMap::new();
        faces.insert("bottom".into(), (0..nx).map(|i| [id(i, 0), id(i + 1, 0)]).collect());
        faces.insert("right".into(), (0..ny).map(|j| [id(nx, j), id(nx, j + 1)]).collect());
        faces.insert(
            "top".into(),
            (0..nx).rev().map(|i| [id(i + 1, ny), id(i, ny)]).collect(),
        );
        faces.insert("left".into(), (0..ny).rev().map(|j| [id(0, j + 1), id(0, j)]).collect());
        RectMesh {
            nodes,
            quads,
            node_sets,
            faces,
        }
    }
}

/// Counter-clockwise quadrilateral mesh of a ring sector `r_in ≤ r ≤ r_out`,
/// `θ_from ≤ θ ≤ θ_to` about `centre` (a curved strip: a belt lying on a cylinder), with
/// `elements = [around, through]`. Node sets `inner`, `outer`, `start` (θ_from), `end`
/// (θ_to), `all`; faces of the same names, each running with the body on its left (`outer`
/// counter-clockwise, `inner` clockwise, `start` outwards, `end` inwards). A full turn is a
/// closed ring: the last column of nodes is the first (`start` and `end` name the same
/// nodes, and there are no `start` and `end` faces), so the ring is not cut along a seam.
pub fn annulus(centre: [f64; 2], radii: [f64; 2], angles_deg: [f64; 2], elements: [usize; 2]) -> RectMesh {
    let around: Vec<f64> = (0..=elements[0]).map(|i| i as f64).collect();
    let through: Vec<f64> = (0..=elements[1]).map(|j| j as f64).collect();
    annulus_on(centre, radii, angles_deg, &around, &through)
}

/// [`annulus`] with the nodes at `around[i]` (from 0 to `na`, in units of a uniform
/// element: the sweep's fraction is `around[i] / na`) and `through[j]` (from 0 at
/// `radii[0]` to `nr` at `radii[1]`), e.g. from [`axis_coords`] with `len = n`; `i` and `j`
/// give the uniform mesh (same bits as [`annulus`] always gave).
pub fn annulus_on(
    centre: [f64; 2],
    radii: [f64; 2],
    angles_deg: [f64; 2],
    around: &[f64],
    through: &[f64],
) -> RectMesh {
    let [na, nr] = [around.len() - 1, through.len() - 1];
    let (t0, t1) = (angles_deg[0].to_radians(), angles_deg[1].to_radians());
    let closed = ((t1 - t0).abs() - std::f64::consts::TAU).abs() < 1e-9;
    let columns = if closed { na } else { na + 1 };
    let id = |i: usize, j: usize| j * columns + i % columns;
    let mut nodes = Vec::with_capacity(columns * (nr + 1));
    for &b in through {
        let r = radii[0] + (radii[1] - radii[0]) * b / nr as f64;
        for &a in &around[..columns] {
            let t = t0 + (t1 - t0) * a / na as f64;
            nodes.push([centre[0] + r * t.cos(), centre[1] + r * t.sin()]);
        }
    }
    // (θ, r) ↦ (x, y) turns the (i, j) grid's orientation when θ increases: order each quad
    // so that it is counter-clockwise whichever way θ runs
    let ccw = (t1 > t0) == (radii[1] > radii[0]);
    let mut quads = Vec::with_capacity(na * nr);
    for j in 0..nr {
        for i in 0..na {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            quads.push(if ccw { [q[0], q[3], q[2], q[1]] } else { q });
        }
    }
    let mut node_sets = BTreeMap::new();
    node_sets.insert("inner".into(), (0..columns).map(|i| id(i, 0)).collect());
    node_sets.insert("outer".into(), (0..columns).map(|i| id(i, nr)).collect());
    node_sets.insert("start".into(), (0..=nr).map(|j| id(0, j)).collect());
    node_sets.insert("end".into(), (0..=nr).map(|j| id(na, j)).collect::<Vec<_>>());
    node_sets.insert("all".into(), (0..nodes.len()).collect());
    let mut faces: BTreeMap<String, Vec<[usize; 2]>> = BTreeMap::new();
    let run = |v: Vec<[usize; 2]>, forward: bool| -> Vec<[usize; 2]> {
        if forward {
            v
        } else {
            v.into_iter().rev().map(|[a, b]| [b, a]).collect()
        }
    };
    let inner: Vec<[usize; 2]> = (0..na).map(|i| [id(i, 0), id(i + 1, 0)]).collect();
    let outer: Vec<[usize; 2]> = (0..na).map(|i| [id(i, nr), id(i + 1, nr)]).collect();
    // counter-clockwise quads: outer runs with i when ccw, start runs with j when ccw
    faces.insert("outer".into(), run(outer, ccw));
    faces.insert("inner".into(), run(inner, !ccw));
    if !closed {
        let start: Vec<[usize; 2]> = (0..nr).map(|j| [id(0, j), id(0, j + 1)]).collect();
        let end: Vec<[usize; 2]> = (0..nr).map(|j| [id(na, j), id(na, j + 1)]).collect();
        faces.insert("start".into(), run(start, ccw));
        faces.insert("end".into(), run(end, !ccw));
    }
    RectMesh {
        nodes,
        quads,
        node_sets,
        faces,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_sets_faces_and_orientation() {
        let m = RectMesh::new([1.0, 2.0], [4.0, 1.0], [4, 2], [1.0, 1.0]);
        assert_eq!(m.nodes.len(), 15);
        assert_eq!(m.quads.len(), 8);
        assert_eq!(m.node_sets["left"], vec![0, 5, 10]);
        assert_eq!(m.node_sets["top-right"], vec![14]);
        // bottom face runs +x: outward normal (ty, -tx) = (0, -1)
        let [a, b] = m.faces["bottom"][0];
        assert!(m.nodes[b][0] > m.nodes[a][0]);
        // top face runs -x
        let [a, b] = m.faces["top"][0];
        assert!(m.nodes[b][0] < m.nodes[a][0]);
        assert_eq!(m.nodes[14], [5.0, 3.0]);
    }

    #[test]
    fn grading_ratio_is_last_over_first() {
        let c = graded_coords(10.0, 5, 4.0);
        let first = c[1] - c[0];
        let last = c[5] - c[4];
        assert!((last / first - 4.0).abs() < 1e-12);
        assert!((c[5] - 10.0).abs() < 1e-15);
    }

    #[test]
    fn a_full_turn_annulus_is_a_closed_ring() {
        for angles in [[75.0, 435.0], [360.0, 0.0]] {
            let m = annulus([0.0, 0.0], [1.0, 1.1], angles, [12, 2]);
            assert_eq!(m.nodes.len(), 12 * 3, "{angles:?}");
            assert_eq!(m.node_sets["start"], m.node_sets["end"]);
            assert!(!m.faces.contains_key("start") && !m.faces.contains_key("end"));
            // every node is used, and the outer face is a closed chain
            let mut used = vec![false; m.nodes.len()];
            m.quads.iter().flatten().for_each(|&n| used[n] = true);
            assert!(used.iter().all(|u| *u));
            let outer = &m.faces["outer"];
            assert_eq!(outer.len(), 12);
            assert!(outer.windows(2).all(|w| w[0][1] == w[1][0]) && outer[11][1] == outer[0][0]);
        }
    }

    #[test]
    fn annulus_quads_are_counter_clockwise_and_faces_keep_the_body_on_their_left() {
        for angles in [[0.0, 180.0], [180.0, 0.0]] {
            let m = annulus([0.0, 0.0], [1.0, 1.1], angles, [12, 2]);
            let area = |q: &[usize; 4]| {
                let p = q.map(|n| m.nodes[n]);
                (0..4)
                    .map(|i| p[i][0] * p[(i + 1) % 4][1] - p[(i + 1) % 4][0] * p[i][1])
                    .sum::<f64>()
            };
            assert!(m.quads.iter().all(|q| area(q) > 0.0), "{angles:?}");
            // the body lies to the left of every face segment: the centre of the element that
            // has the segment as an edge is on its left
            for (name, face) in &m.faces {
                for &[a, b] in face {
                    let q = m.quads.iter().find(|q| q.contains(&a) && q.contains(&b)).unwrap();
                    let c = q.iter().fold([0.0, 0.0], |s, &n| {
                        [s[0] + m.nodes[n][0] / 4.0, s[1] + m.nodes[n][1] / 4.0]
                    });
                    let (pa, pb) = (m.nodes[a], m.nodes[b]);
                    let cross = (pb[0] - pa[0]) * (c[1] - pa[1]) - (pb[1] - pa[1]) * (c[0] - pa[0]);
                    assert!(cross > 0.0, "{name} {angles:?}");
                }
            }
        }
    }
}
