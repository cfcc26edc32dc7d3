//! Order conditions of explicit Runge–Kutta methods of any order, from rooted trees (Butcher;
//! Hairer, Nørsett & Wanner I, II.2): a method has order p when `Σ_i b_i Φ_i(τ) = 1/γ(τ)` for
//! every rooted tree τ with at most p nodes, where `Φ(•) = 1` and, for a tree whose root has
//! subtrees τ_1 … τ_m, `Φ_i(τ) = Π_k (A Φ(τ_k))_i` and `γ(τ) = |τ| Π_k γ(τ_k)`.
//!
//! There are 1, 1, 2, 4, 9, 20, 48, 115, 286, 719 trees with 1 … 10 nodes.

use super::Tableau;

/// Every rooted tree with at most `max_order` nodes, each as the indices of its root's subtrees
/// (non-increasing, so each tree appears once), with its order; trees are listed by order.
pub fn rooted_trees(max_order: usize) -> Vec<(Vec<usize>, usize)> {
    let mut trees: Vec<(Vec<usize>, usize)> = Vec::new();
    if max_order == 0 {
        return trees;
    }
    trees.push((Vec::new(), 1));
    for n in 2..=max_order {
        let mut new = Vec::new();
        collect(&trees, n - 1, trees.len() - 1, &mut Vec::new(), &mut new);
        trees.extend(new.into_iter().map(|f| (f, n)));
    }
    trees
}

/// Appends to `out` every forest (multiset of known trees, as non-increasing indices ≤
/// `max_index`) whose orders sum to `total`.
fn collect(
    trees: &[(Vec<usize>, usize)],
    total: usize,
    max_index: usize,
    forest: &mut Vec<usize>,
    out: &mut Vec<Vec<usize>>,
) {
    if total == 0 {
        out.push(forest.clone());
        return;
    }
    for idx in (0..=max_index).rev() {
        if trees[idx].1 <= total {
            forest.push(idx);
            collect(trees, total - trees[idx].1, idx, forest, out);
            forest.pop();
        }
    }
}

/// For each order 1 ..= max_order, the largest residual `|b·Φ(τ) − 1/γ(τ)|` over its trees,
/// scaled by the size of the terms summed (`Σ |b_i| |Φ|_i(τ)` with |A|, at least 1/γ), so a
/// residual near 1e-16 means "holds to rounding" whatever the size of the coefficients.
pub fn order_residuals(tab: &Tableau, max_order: usize) -> Vec<f64> {
    let s = tab.stages();
    let trees = rooted_trees(max_order);
    let mut phi: Vec<Vec<f64>> = Vec::with_capacity(trees.len());
    let mut phi_abs: Vec<Vec<f64>> = Vec::with_capacity(trees.len());
    let mut gamma: Vec<f64> = Vec::with_capacity(trees.len());
    let mut worst = vec![0.0f64; max_order];
    for (children, order) in &trees {
        let mut v = vec![1.0; s];
        let mut va = vec![1.0; s];
        let mut g = *order as f64;
        for &ch in children {
            for i in 0..s {
                let (mut w, mut wa) = (0.0, 0.0);
                for j in 0..i {
                    w += tab.a[i][j] * phi[ch][j];
                    wa += tab.a[i][j].abs() * phi_abs[ch][j];
                }
                v[i] *= w;
                va[i] *= wa;
            }
            g *= gamma[ch];
        }
        let sum: f64 = (0..s).map(|i| tab.b[i] * v[i]).sum();
        let scale: f64 = (0..s).map(|i| tab.b[i].abs() * va[i]).sum::<f64>();
        let r = (sum - 1.0 / g).abs() / scale.max(1.0 / g);
        worst[order - 1] = worst[order - 1].max(if r.is_nan() { f64::INFINITY } else { r });
        phi.push(v);
        phi_abs.push(va);
        gamma.push(g);
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tree_counts_are_butchers() {
        let trees = rooted_trees(10);
        let counts: Vec<usize> = (1..=10)
            .map(|n| trees.iter().filter(|t| t.1 == n).count())
            .collect();
        assert_eq!(counts, [1, 1, 2, 4, 9, 20, 48, 115, 286, 719]);
    }

    #[test]
    fn rk4_has_order_four_exactly() {
        let r = order_residuals(&Tableau::rk4(), 5);
        assert!(r[..4].iter().all(|&v| v < 1e-15), "{r:?}");
        assert!(r[4] > 1e-3, "{r:?}");
        let r = order_residuals(&Tableau::rk4_typo(), 2);
        assert!(r[1] > 1e-3, "{r:?}");
    }
}
