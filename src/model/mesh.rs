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

impl RectMesh {
    /// `origin` is the bottom-left corner; `grading = [rx, ry]` is the ratio of last to first
    /// element size along x and y (1 = uniform).
    pub fn new(origin: [f64; 2], size: [f64; 2], elements: [usize; 2], grading: [f64; 2]) -> Self {
        let [nx, ny] = elements;
        let xs = graded_coords(size[0], nx, grading[0]);
        let ys = graded_coords(size[1], ny, grading[1]);
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        for y in &ys {
            for x in &xs {
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
}
