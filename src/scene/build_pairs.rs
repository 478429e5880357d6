//! Contact pairs a scene implies besides those it lists: the second pass of a two-pass pair,
//! the convex vertices of a rigid outline as slave points, and which pair owns which vertex.

use super::build::{body_index, Ctx};
use super::types::ContactSpec;
use super::SceneError;
use crate::model::{
    chain_neighbours, ContactLaw, ContactPair, Master, Model, OwnedVertex, RigidShape, Slave, SECOND_PASS_SUFFIX,
};

/// Smallest turn (radians) at a joint of a rigid outline that counts as a vertex: a fillet
/// joined tangentially to its lines has none, a polygon of 1000 facets turns 0.0063 rad.
pub const VERTEX_TURN: f64 = 1e-4;

/// The face of body `body` made of its boundary edges whose two ends are both in `nodes`
/// (body on the left, as every face); empty when the nodes span no edge.
pub fn face_of(m: &Model, body: usize, nodes: &[Slave]) -> Vec<[usize; 2]> {
    let set: std::collections::HashSet<usize> = nodes
        .iter()
        .filter_map(|s| match s {
            Slave::Node(n) => Some(*n),
            _ => None,
        })
        .collect();
    m.boundary_segments(body)
        .into_iter()
        .filter(|[a, b]| set.contains(a) && set.contains(b))
        .collect()
}

fn face_master(body: usize, segments: Vec<[usize; 2]>) -> Master {
    let (prev, next) = chain_neighbours(&segments);
    Master::Face {
        body,
        segments,
        prev,
        next,
    }
}

fn halved(law: ContactLaw) -> ContactLaw {
    ContactLaw {
        eps_n: 0.5 * law.eps_n,
        eps_t: 0.5 * law.eps_t,
        mu: law.mu,
    }
}

/// Make `pair` (slave nodes of `slave_body` on a deformable face) the first pass of a
/// two-pass pair: both passes get half its penalties; returns the second pass (the face's
/// nodes on the face of the slave nodes), or `None` when the slave nodes span no face.
///
/// Why: one-pass node-to-segment between non-matching meshes does not transmit a uniform
/// pressure — the slave nodes' forces reach the master nodes through the master's shape
/// functions, not as the master's consistent nodal loads (Taylor & Papadopoulos 1991; the
/// contact patch test). With both passes each side's nodes are also held on the other face,
/// and a uniform pressure is an equilibrium of the pair to within the penalty's compliance.
pub fn second_pass(m: &Model, pair: &mut ContactPair, slave_body: usize) -> Option<ContactPair> {
    let Master::Face { segments, .. } = &pair.master else {
        return None;
    };
    let face = face_of(m, slave_body, &pair.slaves);
    if face.is_empty() {
        return None;
    }
    let mut nodes: Vec<usize> = segments.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    pair.law = halved(pair.law);
    Some(ContactPair {
        name: format!("{}{SECOND_PASS_SUFFIX}", pair.name),
        slaves: nodes.into_iter().map(Slave::Node).collect(),
        master: face_master(slave_body, face),
        law: pair.law,
        transfer: pair.transfer,
        search_radius: pair.search_radius,
        owned_vertices: Vec::new(),
        weights: Vec::new(),
        smoothing: pair.smoothing,
        enforcement: pair.enforcement,
    })
}

/// The convex vertices of rigid body `body`'s outline: joints of two pieces that turn left
/// (towards the solid, which lies on the left of travel) by more than [`VERTEX_TURN`].
pub fn convex_vertices(m: &Model, body: usize) -> Vec<usize> {
    let RigidShape::Surface { pieces } = &m.rigid[body].shape else {
        return Vec::new();
    };
    (1..pieces.len())
        .filter(|&v| {
            let (_, a) = pieces[v - 1].eval(1.0);
            let (_, b) = pieces[v].eval(-1.0);
            let cross = a[0] * b[1] - a[1] * b[0];
            let dot = a[0] * b[0] + a[1] * b[1];
            cross.atan2(dot) > VERTEX_TURN
        })
        .collect()
}

/// For `pair` (slave nodes of `slave_body` on a rigid outline): the pair of the outline's
/// convex vertices against the face of those nodes, named `NAME/vertices`, with the same law
/// and transfer scheme; vertices that are already slaves of some pair in `taken` are left
/// out. `None` when there is no such vertex or the nodes span no face.
///
/// Why: node-to-segment sees the nodes of the face, not the corners of the outline. Where a
/// face wraps a convex corner of a rigid polygon (a sheet pulled over it, a punch's edge)
/// the corner lies between two nodes and pokes through the face between them; the face
/// bends at the two nodes instead of at the corner (measured: force ratios over a polygon
/// 4–10 % off the rope statics). With the corner as a slave point on the face, the face
/// bends where the corner is (the strip-channel's corner C is such a point, named by its
/// scene); [`own_vertices`] then keeps the face's nodes next to it from meeting the
/// outline's pieces there as well.
pub fn vertex_pair(m: &Model, pair: &ContactPair, slave_body: usize, taken: &[(usize, usize)]) -> Option<ContactPair> {
    let Master::Rigid { body, .. } = pair.master else {
        return None;
    };
    let vertices: Vec<Slave> = convex_vertices(m, body)
        .into_iter()
        .filter(|v| !taken.contains(&(body, *v)))
        .map(|v| Slave::RigidVertex(body, v))
        .collect();
    let face = face_of(m, slave_body, &pair.slaves);
    if vertices.is_empty() || face.is_empty() {
        return None;
    }
    Some(ContactPair {
        name: format!("{}/vertices", pair.name),
        slaves: vertices,
        master: face_master(slave_body, face),
        law: pair.law,
        transfer: pair.transfer,
        search_radius: pair.search_radius,
        owned_vertices: Vec::new(),
        weights: Vec::new(),
        // a rigid master's pair keeps the smoothing of the face its vertices press on
        smoothing: pair.smoothing,
        enforcement: pair.enforcement,
    })
}

/// Mark, on every pair whose master is a rigid outline, the vertices of that outline that are
/// slave points of some pair (their owner; see `contact::pairing`, rule 4).
pub fn own_vertices(m: &mut Model) {
    let mut owners = Vec::new();
    for (ip, p) in m.contacts.iter().enumerate() {
        for (is, s) in p.slaves.iter().enumerate() {
            if let Slave::RigidVertex(body, vertex) = *s {
                owners.push((
                    body,
                    OwnedVertex {
                        vertex,
                        owner: ip,
                        slave: is,
                    },
                ));
            }
        }
    }
    for pair in &mut m.contacts {
        if let Master::Rigid { body, .. } = pair.master {
            pair.owned_vertices = owners.iter().filter(|(b, _)| *b == body).map(|(_, o)| *o).collect();
        }
    }
}

/// A pair a scene's `[[contact]]` implies besides itself.
pub(super) enum Implied {
    /// The second pass of a two-pass pair.
    SecondPass(Box<ContactPair>),
    /// The convex vertices of the rigid master of the pair with this index.
    Vertices(usize),
}

/// The pairs `c` implies (`pair` is its first pass; with its slave body): the second pass of
/// a two-pass pair (which halves `pair`'s penalties), or the vertices of its rigid master.
pub(super) fn implied_pairs(
    cx: &Ctx,
    m: &Model,
    c: &ContactSpec,
    pair: &mut ContactPair,
) -> Result<Vec<(Implied, usize)>, SceneError> {
    let slave_body = c.slave.body.as_deref().map(|b| body_index(cx, m, b)).transpose()?;
    let mut out = Vec::new();
    match (&pair.master, slave_body) {
        (Master::Face { .. }, Some(sb)) if c.two_pass => {
            let second = second_pass(m, pair, sb).ok_or_else(|| {
                cx.err(
                    &c.name,
                    format!(
                        "contact `{}`: two_pass needs slave nodes that span a face of their body",
                        c.name
                    ),
                    "give `slave.nodes` a set of boundary nodes (e.g. \"bottom\"), or set two_pass = false",
                )
            })?;
            out.push((Implied::SecondPass(Box::new(second)), sb));
        }
        _ if c.two_pass => {
            return Err(cx.err(
                &c.name,
                format!(
                    "contact `{}`: two_pass is for slave nodes on the face of another deformable body",
                    c.name
                ),
                "use `slave = { body, nodes }` with `master = { body, face }`, or remove two_pass",
            ))
        }
        (Master::Rigid { .. }, Some(sb)) if c.vertices => out.push((Implied::Vertices(m.contacts.len()), sb)),
        _ => {}
    }
    Ok(out)
}

/// The segments of a named face, or of a union of faces named `a+b` (the corner between
/// them joins the chain: the top and the wall of a block as one master, as a rigid
/// polyline would be). `None` when a part is not a face of the body.
pub fn face_union(faces: &std::collections::BTreeMap<String, Vec<[usize; 2]>>, name: &str) -> Option<Vec<[usize; 2]>> {
    let mut segments = Vec::new();
    for part in name.split('+').map(str::trim) {
        for s in faces.get(part)? {
            if !segments.contains(s) {
                segments.push(*s);
            }
        }
    }
    Some(segments)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(scene: &str) -> Model {
        crate::load_scene(scene, &[]).unwrap().1.model
    }

    #[test]
    fn the_strip_channels_corner_is_its_only_convex_vertex() {
        let m = model("strip-channel");
        assert_eq!(convex_vertices(&m, 0), vec![1]);
        // named by the scene: no pair of vertices is added
        assert!(m.contacts.iter().all(|c| !c.name.ends_with("/vertices")));
        assert_eq!(
            m.contacts[1].owned_vertices,
            vec![OwnedVertex {
                vertex: 1,
                owner: 0,
                slave: 0
            }]
        );
    }

    #[test]
    fn the_face_of_a_node_set_runs_with_the_body_on_its_left() {
        let m = model("hertz");
        let top = &m.bodies[0].node_sets["top"];
        let slaves: Vec<Slave> = top.iter().map(|&n| Slave::Node(n)).collect();
        let face = face_of(&m, 0, &slaves);
        assert_eq!(face.len(), top.len() - 1);
        let mut expected = m.bodies[0].faces["top"].clone();
        let mut got = face.clone();
        expected.sort_unstable();
        got.sort_unstable();
        assert_eq!(got, expected);
    }

    #[test]
    fn a_union_of_faces_is_one_chain_through_their_corner() {
        let faces: std::collections::BTreeMap<String, Vec<[usize; 2]>> =
            [("top".to_string(), vec![[3, 2]]), ("left".to_string(), vec![[2, 0]])].into();
        let both = super::face_union(&faces, "top + left").unwrap();
        assert_eq!(both, vec![[3, 2], [2, 0]]);
        let (prev, next) = crate::model::chain_neighbours(&both);
        assert_eq!((next[0], prev[1]), (Some(1), Some(0)));
        assert_eq!(super::face_union(&faces, "top+top"), Some(vec![[3, 2]]));
        assert!(super::face_union(&faces, "top+wall").is_none());
    }
}
