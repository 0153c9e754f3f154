//! The node tree of a glTF scene: each node's world transform (its
//! parents' matrices or translation–rotation–scale composed in f64), in
//! a walk that refuses what is not a tree (a node its own ancestor, or
//! the child of two parents) rather than looping or multiplying.

use glam::{DMat4, DQuat, DVec3};

use super::{Fault, GltfProblem};

/// A node as the walk reaches it.
pub(super) struct Placed {
    /// Its index in `nodes`.
    pub(super) node: usize,
    /// Its world transform.
    pub(super) world: DMat4,
    /// Whether it is the node asked for or lies under it.
    pub(super) inside: bool,
}

/// A problem with node `n`.
fn fault(n: usize, what: &str, problem: String) -> Fault {
    (format!("nodes[{n}]{what}"), GltfProblem::Nodes(problem))
}

/// A node's own transform, every number finite.
fn local(node: &gltf::Node<'_>) -> Result<DMat4, Fault> {
    let n = node.index();
    let finite = |what: &str, v: &[f32]| {
        if v.iter().all(|x| x.is_finite()) { Ok(()) } else { Err(fault(n, what, format!("{v:?} is not finite"))) }
    };
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            finite(".matrix", matrix.as_flattened())?;
            Ok(DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from))))
        }
        gltf::scene::Transform::Decomposed { translation: t, rotation: r, scale: s } => {
            finite(".translation", &t)?;
            finite(".rotation", &r)?;
            finite(".scale", &s)?;
            let d = |v: [f32; 3]| DVec3::from_array(v.map(f64::from));
            let q = DQuat::from_array(r.map(f64::from));
            Ok(DMat4::from_scale_rotation_translation(d(s), q, d(t)))
        }
    }
}

/// Every node of the document's scene (its default, or its first, or
/// where it has none every node no other names as a child), in depth-first
/// order, each with its world transform; `inside` marks node `under` and
/// its descendants.
pub(super) fn walk(document: &gltf::Document, under: Option<usize>) -> Result<Vec<Placed>, Fault> {
    let count = document.nodes().len();
    let mut parent: Vec<Option<usize>> = vec![None; count];
    for node in document.nodes() {
        for child in node.children() {
            let c = child.index();
            if let Some(p) = parent[c] {
                let problem = format!("is the child of both nodes[{p}] and nodes[{}]; nodes form trees", node.index());
                return Err(fault(c, "", problem));
            }
            parent[c] = Some(node.index());
        }
    }
    let roots: Vec<usize> = match document.default_scene().or_else(|| document.scenes().next()) {
        Some(scene) => scene.nodes().map(|n| n.index()).collect(),
        None => (0..count).filter(|&n| parent[n].is_none()).collect(),
    };
    let nodes: Vec<gltf::Node<'_>> = document.nodes().collect();
    let mut seen = vec![false; count];
    let mut out = Vec::new();
    // (node, its parent's world transform, whether the parent is inside)
    let mut stack: Vec<(usize, DMat4, bool)> = roots.iter().rev().map(|&n| (n, DMat4::IDENTITY, false)).collect();
    while let Some((n, above, parent_inside)) = stack.pop() {
        if std::mem::replace(&mut seen[n], true) {
            return Err(fault(n, "", "is reached twice: it is its own ancestor, or a root twice over".into()));
        }
        let node = &nodes[n];
        let world = above * local(node)?;
        let inside = parent_inside || under == Some(n);
        out.push(Placed { node: n, world, inside });
        stack.extend(node.children().map(|c| (c.index(), world, inside)).collect::<Vec<_>>().into_iter().rev());
    }
    Ok(out)
}
