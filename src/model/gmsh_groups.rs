//! From a Gmsh file's physical groups to a body's node sets and faces: which edges of the
//! quadrilaterals are on the boundary, and the sets and chained faces of each group.

use super::*;

/// Each edge of the quadrilaterals (by its sorted ends): how many elements share it, and its
/// orientation in the first (counter-clockwise around the body: body on the left). Boundary
/// edges have a count of 1.
pub(super) type Edges = HashMap<(usize, usize), (usize, [usize; 2])>;

pub(super) fn boundary_edges(quads: &[[usize; 4]]) -> Edges {
    let mut edges: Edges = HashMap::new();
    for q in quads {
        for i in 0..4 {
            let (a, b) = (q[i], q[(i + 1) % 4]);
            edges.entry((a.min(b), a.max(b))).or_insert((0, [a, b])).0 += 1;
        }
    }
    edges
}

/// The physical groups of a file, to turn into node sets and faces.
pub(super) struct Groups<'a> {
    pub(super) file: &'a str,
    /// Name of each physical group by (dimension, tag).
    pub(super) names: &'a HashMap<(i32, i32), String>,
    /// Physical groups of each entity by (dimension, entity tag).
    pub(super) groups: &'a HashMap<(i32, i32), Vec<i32>>,
    /// Node index of each used node tag.
    pub(super) index: &'a HashMap<u64, usize>,
}

/// Node sets by group name, faces by curve name, and the curves that are not on the boundary
/// (with how many of their lines are inside).
type SetsAndFaces = (
    BTreeMap<String, Vec<usize>>,
    BTreeMap<String, Vec<[usize; 2]>>,
    Vec<(String, usize)>,
);

impl Groups<'_> {
    fn name(&self, dim: i32, tag: i32) -> String {
        self.names.get(&(dim, tag)).cloned().unwrap_or_else(|| tag.to_string())
    }

    fn of(&self, dim: i32, entity: i32) -> Vec<i32> {
        self.groups.get(&(dim, entity)).cloned().unwrap_or_default()
    }

    /// Add the nodes `tags` to the set `name`; a node no quadrilateral uses is refused.
    fn add_nodes(
        &self,
        sets: &mut BTreeMap<String, Vec<usize>>,
        name: &str,
        tags: &mut dyn Iterator<Item = u64>,
    ) -> Result<(), GmshError> {
        let set = sets.entry(name.to_string()).or_default();
        for t in tags {
            let i = *self.index.get(&t).ok_or_else(|| GmshError::NodeOffBody {
                file: self.file.into(),
                group: name.into(),
                node: t,
            })?;
            set.push(i);
        }
        Ok(())
    }

    /// Node sets of the physical points, curves and surfaces; a physical curve on the
    /// boundary is also a face (its segments chained, oriented with the body on the left).
    pub(super) fn sets_and_faces(&self, sorted: &Sorted, edges: &Edges) -> Result<SetsAndFaces, GmshError> {
        let mut node_sets: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        let mut curve_lines: BTreeMap<String, Vec<[u64; 2]>> = BTreeMap::new();
        for (&entity, pts) in &sorted.points {
            for g in self.of(0, entity) {
                self.add_nodes(&mut node_sets, &self.name(0, g), &mut pts.iter().copied())?;
            }
        }
        for (&entity, lines) in &sorted.lines {
            for g in self.of(1, entity) {
                let name = self.name(1, g);
                self.add_nodes(&mut node_sets, &name, &mut lines.iter().flatten().copied())?;
                curve_lines.entry(name).or_default().extend(lines);
            }
        }
        for (_, q, entity) in &sorted.quads {
            for g in self.of(2, *entity) {
                self.add_nodes(&mut node_sets, &self.name(2, g), &mut q.iter().copied())?;
            }
        }
        let mut faces = BTreeMap::new();
        let mut interior_curves = Vec::new();
        for (name, lines) in curve_lines {
            let mut segments = Vec::with_capacity(lines.len());
            let mut inside = 0;
            for [a, b] in lines {
                let (a, b) = (self.index[&a], self.index[&b]);
                match edges.get(&(a.min(b), a.max(b))) {
                    Some(&(1, seg)) => segments.push(seg),
                    _ => inside += 1,
                }
            }
            if inside > 0 {
                interior_curves.push((name, inside));
            } else {
                faces.insert(name, chain(segments));
            }
        }
        for set in node_sets.values_mut() {
            set.sort_unstable();
            set.dedup();
        }
        Ok((node_sets, faces, interior_curves))
    }
}
