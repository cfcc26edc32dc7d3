//! Typeset maths through the public API: Typst and LaTeX input, errors with positions, the
//! egui cache and its last-good behaviour.

use lectern::math::{MathCache, MathSyntax, latex_to_typst, render_formula};

const BLACK: [u8; 4] = [0, 0, 0, 255];

fn ink(f: &lectern::math::RenderedFormula) -> usize {
    f.rgba_premultiplied
        .chunks(4)
        .filter(|p| p[3] > 128)
        .count()
}

#[test]
fn textbook_constructs_render() {
    for src in [
        "dot(x) = f(x, t)",
        "x(t + h) = x(t) + h dot(x)(t) + h^2/2 dot.double(x)(t) + dots.c",
        "bold(X) = vec(bold(x), bold(q), bold(P), bold(L))",
        "I^(-1)(t) = R(t) I_\"body\"^(-1) R(t)^T",
        "mat(0, -omega_z, omega_y; omega_z, 0, -omega_x; -omega_y, omega_x, 0)",
    ] {
        let f = render_formula(src, MathSyntax::Typst, 48.0, BLACK)
            .unwrap_or_else(|e| panic!("{src}: {e}"));
        assert!(ink(&f) > 200, "{src}: almost no ink");
    }
}

#[test]
fn size_scales_the_raster() {
    let small = render_formula("x^2 + y^2", MathSyntax::Typst, 20.0, BLACK).unwrap();
    let large = render_formula("x^2 + y^2", MathSyntax::Typst, 80.0, BLACK).unwrap();
    let r = large.height as f64 / small.height as f64;
    assert!((3.5..4.5).contains(&r), "height ratio {r}");
}

#[test]
fn colour_is_applied() {
    let f = render_formula("bold(M) + x", MathSyntax::Typst, 100.0, [200, 0, 0, 255]).unwrap();
    // solid ink (stroke interiors) carries the colour exactly; edges are antialiased
    let solid: Vec<&[u8]> = f
        .rgba_premultiplied
        .chunks(4)
        .filter(|p| p[3] >= 250)
        .collect();
    assert!(solid.len() > 20, "{} solid pixels", solid.len());
    assert!(solid.iter().all(|p| p[0] > 190 && p[1] < 10 && p[2] < 10));
    assert!(
        f.rgba_premultiplied
            .chunks(4)
            .all(|p| p[1] == 0 && p[2] == 0)
    );
}

#[test]
fn latex_and_typst_give_the_same_picture_for_a_fraction() {
    let t = render_formula("(k_1)/6 + sqrt(2)", MathSyntax::Typst, 40.0, BLACK).unwrap();
    let l = render_formula(r"\frac{k_1}{6} + \sqrt{2}", MathSyntax::Latex, 40.0, BLACK).unwrap();
    assert_eq!((t.width, t.height), (l.width, l.height));
    assert!(latex_to_typst(r"\dot{x} = \omega").unwrap().contains("dot"));
}

#[test]
fn broken_formulas_report_where() {
    let e = render_formula("x = frac(1,", MathSyntax::Typst, 40.0, BLACK).unwrap_err();
    assert!(e.col.is_some(), "{e}");
    let e = render_formula("x + undefinedthing(2)", MathSyntax::Typst, 40.0, BLACK).unwrap_err();
    assert_eq!(e.col, Some(5), "{e}");
    assert!(e.message.contains("unknown"), "{e}");
    let e = render_formula(r"\frac{1}{2}}", MathSyntax::Latex, 40.0, BLACK).unwrap_err();
    assert!(e.message.starts_with("LaTeX"), "{e}");
    assert!(render_formula("x", MathSyntax::Typst, f32::NAN, BLACK).is_err());
    assert!(render_formula("x", MathSyntax::Typst, 1e9, BLACK).is_err());
    assert!(render_formula("  ", MathSyntax::Typst, 40.0, BLACK).is_err());
}

#[test]
fn cache_hits_and_keeps_the_last_good_rendering() {
    let ctx = egui::Context::default();
    let mut cache = MathCache::new();
    let black = egui::Color32::BLACK;
    let a = cache
        .get(&ctx, "x^2", MathSyntax::Typst, 40.0, black)
        .unwrap();
    let b = cache
        .get(&ctx, "x^2", MathSyntax::Typst, 40.0, black)
        .unwrap();
    assert_eq!(a.texture.id(), b.texture.id(), "same key, same texture");
    assert_eq!(cache.renders, 1);
    let c = cache
        .get(&ctx, "x^2", MathSyntax::Typst, 40.0, egui::Color32::RED)
        .unwrap();
    assert_ne!(a.texture.id(), c.texture.id(), "colour is part of the key");
    let d = cache
        .get(&ctx, "x^2", MathSyntax::Typst, 41.0, black)
        .unwrap();
    assert_ne!(a.texture.id(), d.texture.id(), "size is part of the key");

    let good = cache.get_slot(&ctx, "s/0", "a + b", MathSyntax::Typst, 40.0, black);
    assert!(good.error.is_none());
    let good_id = good.formula.unwrap().texture.id();
    let bad = cache.get_slot(&ctx, "s/0", "a + frac(b", MathSyntax::Typst, 40.0, black);
    assert!(bad.error.is_some(), "the broken edit reports its error");
    assert_eq!(
        bad.formula.unwrap().texture.id(),
        good_id,
        "and the last good picture stays"
    );
    let renders = cache.renders;
    let _ = cache.get_slot(&ctx, "s/0", "a + frac(b", MathSyntax::Typst, 40.0, black);
    assert_eq!(cache.renders, renders, "errors are cached too");
}

/// `\sqrt[n]{x}` (mitex keeps LaTeX's brackets around the index) draws exactly Typst's
/// `root(n, x)`: the index without brackets.
#[test]
fn latex_roots_with_an_index_match_typst_root() {
    for (latex, typst) in [
        (r"\sqrt[3]{x}", "root(3, x)"),
        (r"\sqrt[n]{x+1}", "root(n, x+1)"),
        (r"\sqrt[n+1]{x}", "root(n+1, x)"),
        (r"\sqrt{x}", "sqrt(x)"),
    ] {
        let l = render_formula(latex, MathSyntax::Latex, 40.0, BLACK).unwrap();
        let t = render_formula(typst, MathSyntax::Typst, 40.0, BLACK).unwrap();
        assert_eq!((l.width, l.height), (t.width, t.height), "{latex}");
        assert!(l.rgba_premultiplied == t.rgba_premultiplied, "{latex}");
    }
    // the brackets are not drawn: `[3]` as index would be wider than `3`
    let bracketed = render_formula("root([3], x)", MathSyntax::Typst, 40.0, BLACK).unwrap();
    let l = render_formula(r"\sqrt[3]{x}", MathSyntax::Latex, 40.0, BLACK).unwrap();
    assert!(l.width < bracketed.width);
    // an empty index is a plain root, not an error
    assert!(render_formula(r"\sqrt[]{x}", MathSyntax::Latex, 40.0, BLACK).is_ok());
}
