//! Right-hand sides written as text: parsed once ([`parse`]), compiled to a flat register
//! program ([`program`]) and evaluated without allocation.

pub mod derive;
pub mod greek;
pub mod parse;
pub mod program;

pub use derive::derivatives;
pub use parse::{ExprError, Node, Scope, is_reserved, parse};
pub use program::Program;

/// Whether any of `exprs` names `param` (as written, or in its other Greek spelling).
pub fn mentions(exprs: &[String], param: &str) -> bool {
    let alias = greek::alias(param);
    (exprs.iter().flat_map(|e| parse::names(e)))
        .any(|n| n == param || alias.as_deref() == Some(n.as_str()))
}

/// Parses and compiles expressions over `[t, vars…]` with named parameters; the error
/// carries the index of the failing expression.
pub fn compile(
    exprs: &[String],
    vars: &[String],
    params: &[(String, f64)],
) -> Result<Program, (usize, ExprError)> {
    let mut inputs = vec!["t".to_string()];
    inputs.extend(vars.iter().cloned());
    let scope = Scope {
        inputs: &inputs,
        params,
    };
    let nodes = exprs
        .iter()
        .enumerate()
        .map(|(i, e)| parse(e, &scope).map_err(|err| (i, err)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Program::compile(inputs.len(), &nodes))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(v: &[&str]) -> Vec<String> {
        v.iter().map(|x| x.to_string()).collect()
    }

    fn eval1(e: &str, x: f64) -> f64 {
        let p = compile(&s(&[e]), &s(&["x"]), &[("w".into(), 2.0)]).unwrap();
        let mut out = [0.0];
        p.eval(0.5, &[x], &mut out);
        out[0]
    }

    #[test]
    fn precedence_and_associativity() {
        assert_eq!(eval1("1 + 2 * 3", 0.0), 7.0);
        assert_eq!(eval1("-x^2", 3.0), -9.0);
        assert_eq!(eval1("2^3^2", 0.0), 512.0);
        assert_eq!(eval1("(1 + 2) * 3", 0.0), 9.0);
        assert_eq!(eval1("8 / 4 / 2", 0.0), 1.0);
        assert_eq!(eval1("10 - 4 - 3", 0.0), 3.0);
        assert_eq!(eval1("2^-1", 0.0), 0.5);
        assert_eq!(eval1("w * t + x", 1.0), 2.0);
        assert_eq!(
            eval1("max(x, 1e-3) + min(2, pow(2, 3)) + abs(-1.5e0)", 0.0),
            3.501
        );
        assert_eq!(eval1("atan2(1, 1) * 4", 0.0), std::f64::consts::PI);
        assert_eq!(eval1("x^0.5", 4.0), 2.0);
    }

    #[test]
    fn shared_subexpressions_and_folded_parameters() {
        let p = compile(
            &s(&["-x/(x*x+y*y)^1.5", "-y/(x*x+y*y)^1.5", "w*w*x"]),
            &s(&["x", "y"]),
            &[("w".into(), 3.0)],
        )
        .unwrap();
        // x*x, y*y, sum, const 1.5, pow, neg x, div, neg y, div, const 9, mul = 11
        assert_eq!(p.len(), 11, "{p:?}");
    }

    #[test]
    fn errors_point_at_the_offending_token() {
        let vars = s(&["x", "v"]);
        let cases = [
            ("v + q", 4, "q", "unknown name"),
            ("v + ", 4, "end of expression", "ended early"),
            ("sin(x", 5, "end of expression", "expected `)`"),
            ("x $ 2", 2, "$", "unexpected character"),
            ("atan2(x)", 0, "atan2", "2 argument"),
            ("foo(x)", 0, "foo", "unknown function"),
            ("x v", 2, "v", "after a complete"),
            ("sin + 1", 0, "sin", "needs arguments"),
            ("(x))", 3, ")", "after a complete"),
            ("* x", 0, "*", "expected a number"),
            (
                "x*(",
                3,
                "end of expression",
                "expected `)` to close the `(` at column 3",
            ),
            (
                "sin(",
                4,
                "end of expression",
                "expected `)` to close the `(` at column 4",
            ),
            (
                "(x + (v)",
                8,
                "end of expression",
                "expected `)` to close the `(` at column 1",
            ),
            (
                "sinn(x)",
                0,
                "sinn",
                "unknown function `sinn`; did you mean `sin`?",
            ),
            ("vv + x", 0, "vv", "unknown name `vv`; did you mean `v`?"),
        ];
        for (src, offset, token, msg) in cases {
            let (i, e) = compile(&[src.to_string()], &vars, &[]).unwrap_err();
            assert_eq!(i, 0);
            assert_eq!((e.offset, e.token.as_str()), (offset, token), "{src}: {e}");
            assert!(e.message.contains(msg), "{src}: {e}");
        }
    }

    #[test]
    fn mentions_finds_a_parameter_in_either_greek_spelling_and_not_inside_other_names() {
        let e = s(&["-2*zeta*omega*v", "kk*x"]);
        assert!(mentions(&e, "ζ") && mentions(&e, "omega"));
        assert!(!mentions(&e, "k"), "`kk` is not `k`");
        assert!(
            mentions(&s(&["x*("]), "x"),
            "a half-typed equation still names x"
        );
        assert!(
            !mentions(&s(&["x @ k"]), "k"),
            "text that does not lex names nothing"
        );
    }

    #[test]
    fn greek_names_are_typeable_in_ascii_and_the_other_way_round() {
        let vars = s(&["x", "v"]);
        let greek = [("ζ".to_string(), 0.5), ("ω".to_string(), 2.0)];
        let ascii = [("zeta".to_string(), 0.5), ("omega".to_string(), 2.0)];
        let typed = "-2*zeta*omega*v - omega^2*x";
        let written = "-2*ζ*ω*v - ω^2*x";
        let y = [1.0, 0.5];
        let mut out = [0.0];
        for (exprs, params) in [(typed, &greek), (written, &ascii), (written, &greek)] {
            let p = compile(&s(&[exprs]), &vars, params).unwrap();
            p.eval(0.0, &y, &mut out);
            assert_eq!(out[0], -2.0 * 0.5 * 2.0 * 0.5 - 4.0 * 1.0, "{exprs}");
        }
        // a Greek name that is not in scope: a "did you mean" among those that are
        let (_, e) = compile(&s(&["beta*x"]), &vars, &ascii).unwrap_err();
        assert!(e.message.contains("did you mean `zeta`?"), "{e}");
    }
}
