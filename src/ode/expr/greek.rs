//! ASCII spellings of Greek letters, so a name written `ζ` in a problem can be typed `zeta` on
//! any keyboard (and the other way round): `zeta` ↔ `ζ`, `omega` ↔ `ω`, `Omega` ↔ `Ω`, ….

/// (ASCII name, letter): the lower-case letters, then the capitals that differ from Latin ones.
pub const GREEK: &[(&str, &str)] = &[
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("epsilon", "ε"),
    ("zeta", "ζ"),
    ("eta", "η"),
    ("theta", "θ"),
    ("iota", "ι"),
    ("kappa", "κ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("nu", "ν"),
    ("xi", "ξ"),
    ("omicron", "ο"),
    ("rho", "ρ"),
    ("sigma", "σ"),
    ("tau", "τ"),
    ("upsilon", "υ"),
    ("phi", "φ"),
    ("chi", "χ"),
    ("psi", "ψ"),
    ("omega", "ω"),
    ("Gamma", "Γ"),
    ("Delta", "Δ"),
    ("Theta", "Θ"),
    ("Lambda", "Λ"),
    ("Xi", "Ξ"),
    ("Pi", "Π"),
    ("Sigma", "Σ"),
    ("Phi", "Φ"),
    ("Psi", "Ψ"),
    ("Omega", "Ω"),
];

/// The other spelling of `name`: `zeta` → `ζ`, `ζ` → `zeta`, else `None`. A name with a
/// suffix keeps it: `omega0` ↔ `ω0`, `lambda_2` ↔ `λ_2`.
pub fn alias(name: &str) -> Option<String> {
    // the longest ASCII prefix first, so `epsilon` is not read as `e` + …, `eta` not as `e`
    let mut best: Option<(&str, &str)> = None;
    for &(ascii, letter) in GREEK {
        if let Some(rest) = name.strip_prefix(ascii)
            && suffix_ok(rest)
            && best.is_none_or(|(a, _)| a.len() < ascii.len())
        {
            best = Some((ascii, letter));
        }
    }
    if let Some((ascii, letter)) = best {
        return Some(format!("{letter}{}", &name[ascii.len()..]));
    }
    for &(ascii, letter) in GREEK {
        if let Some(rest) = name.strip_prefix(letter)
            && suffix_ok(rest)
        {
            return Some(format!("{ascii}{rest}"));
        }
    }
    None
}

/// A suffix that does not make a longer word of the letter's name (`eta` in `etal`): empty,
/// or digits and underscores first.
fn suffix_ok(rest: &str) -> bool {
    rest.chars()
        .next()
        .is_none_or(|c| c.is_ascii_digit() || c == '_')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_ways_with_suffixes() {
        assert_eq!(alias("zeta").as_deref(), Some("ζ"));
        assert_eq!(alias("ω").as_deref(), Some("omega"));
        assert_eq!(alias("Omega").as_deref(), Some("Ω"));
        assert_eq!(alias("omega0").as_deref(), Some("ω0"));
        assert_eq!(alias("λ_2").as_deref(), Some("lambda_2"));
        assert_eq!(alias("eta").as_deref(), Some("η"));
        assert_eq!(alias("epsilon").as_deref(), Some("ε"));
        assert_eq!(alias("betas"), None);
        assert_eq!(alias("x"), None);
    }
}
