//! A cycle in the graph of a crate's modules, for the module-graph tests of `contact` and `xtask`.

use std::collections::{BTreeMap, BTreeSet};

/// A cycle of `graph` (each module with the modules it uses), as the modules along it with the
/// first repeated at the end (`a -> b -> a`), or None if there is none. Depth-first, modules in
/// the graph's order, so the cycle reported is always the same one.
pub fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn walk(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == node) {
            let mut c = path[i..].to_vec();
            c.push(node.to_owned());
            return Some(c);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node.to_owned());
        for next in graph.get(node).into_iter().flatten() {
            if let Some(c) = walk(next, graph, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(node.to_owned());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| walk(n, graph, &mut Vec::new(), &mut done))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(edges: &[(&str, &[&str])]) -> BTreeMap<String, BTreeSet<String>> {
        edges
            .iter()
            .map(|(m, to)| {
                let to = to.iter().map(|t| (*t).to_owned()).collect();
                ((*m).to_owned(), to)
            })
            .collect()
    }

    #[test]
    fn a_cycle_is_found_and_an_acyclic_graph_passes() {
        let g = graph(&[("a", &["b"]), ("b", &["c"]), ("c", &["a"]), ("d", &["a"])]);
        assert_eq!(
            cycle(&g),
            Some(["a", "b", "c", "a"].map(str::to_owned).to_vec())
        );
        let g = graph(&[("a", &["b", "c"]), ("b", &["c"]), ("c", &[])]);
        assert_eq!(cycle(&g), None);
    }
}
