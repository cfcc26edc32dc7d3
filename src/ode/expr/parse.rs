//! Tokens and a recursive-descent parser for right-hand-side expressions:
//! `+ − * / ^`, unary minus, parentheses, numbers, names, and the functions
//! sin cos tan exp ln sqrt abs (one argument) and atan2 min max pow (two).
//! `^` binds tightest and to the right, so `-x^2 = -(x^2)` and `2^3^2 = 2^9`.

use std::fmt;

/// A parse error: where (0-based char offset into the expression) and which token.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprError {
    pub offset: usize,
    pub token: String,
    pub message: String,
}

impl fmt::Display for ExprError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (at `{}`, column {})",
            self.message,
            self.token,
            self.offset + 1
        )
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Fn1 {
    Neg,
    Sin,
    Cos,
    Tan,
    Exp,
    Ln,
    Sqrt,
    Abs,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Fn2 {
    Add,
    Sub,
    Mul,
    Div,
    Pow,
    Atan2,
    Min,
    Max,
}

/// The expression tree. Names are resolved while parsing: `Input(i)` is slot i of
/// `[t, vars…]`, parameters and constants are already numbers.
#[derive(Debug, Clone, PartialEq)]
pub enum Node {
    Num(f64),
    Input(usize),
    Call1(Fn1, Box<Node>),
    Call2(Fn2, Box<Node>, Box<Node>),
}

#[derive(Debug, Clone, PartialEq)]
enum Tok {
    Num(f64),
    Name(String),
    Sym(char),
    End,
}

struct Token {
    tok: Tok,
    offset: usize,
    text: String,
}

fn lex(src: &str) -> Result<Vec<Token>, ExprError> {
    let chars: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_whitespace() {
            i += 1;
        } else if c.is_ascii_digit()
            || (c == '.' && chars.get(i + 1).is_some_and(|d| d.is_ascii_digit()))
        {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_digit() || chars[i] == '.') {
                i += 1;
            }
            if i < chars.len() && (chars[i] == 'e' || chars[i] == 'E') {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '+' || chars[j] == '-') {
                    j += 1;
                }
                if j < chars.len() && chars[j].is_ascii_digit() {
                    i = j;
                    while i < chars.len() && chars[i].is_ascii_digit() {
                        i += 1;
                    }
                }
            }
            let text: String = chars[start..i].iter().collect();
            let v = text.parse::<f64>().map_err(|_| ExprError {
                offset: start,
                token: text.clone(),
                message: "malformed number".into(),
            })?;
            out.push(Token {
                tok: Tok::Num(v),
                offset: start,
                text,
            });
        } else if c.is_alphabetic() || c == '_' {
            let start = i;
            while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let text: String = chars[start..i].iter().collect();
            out.push(Token {
                tok: Tok::Name(text.clone()),
                offset: start,
                text,
            });
        } else if "+-*/^(),".contains(c) {
            out.push(Token {
                tok: Tok::Sym(c),
                offset: i,
                text: c.to_string(),
            });
            i += 1;
        } else {
            return Err(ExprError {
                offset: i,
                token: c.to_string(),
                message: format!("unexpected character `{c}`"),
            });
        }
    }
    out.push(Token {
        tok: Tok::End,
        offset: chars.len(),
        text: "end of expression".into(),
    });
    Ok(out)
}

/// The names written in `src` (variables, parameters, functions), in order; none if it does
/// not lex.
pub fn names(src: &str) -> Vec<String> {
    let tokens = lex(src).unwrap_or_default();
    (tokens.into_iter())
        .filter_map(|t| match t.tok {
            Tok::Name(n) => Some(n),
            _ => None,
        })
        .collect()
}

/// What names mean: inputs by position in `[t, vars…]`, parameters by value.
pub struct Scope<'a> {
    pub inputs: &'a [String],
    pub params: &'a [(String, f64)],
}

impl Scope<'_> {
    /// A name as written, else its other Greek spelling (`zeta` for a parameter `ζ`).
    fn lookup(&self, name: &str) -> Option<Node> {
        self.lookup_exact(name)
            .or_else(|| super::greek::alias(name).and_then(|a| self.lookup_exact(&a)))
    }

    /// "did you mean" among the names in scope, when one is close to `name`.
    fn suggest(&self, name: &str) -> Option<String> {
        let names = (self.inputs.iter().map(String::as_str))
            .chain(self.params.iter().map(|(n, _)| n.as_str()))
            .chain(["pi"]);
        crate::diag::did_you_mean(name, names)
    }

    fn lookup_exact(&self, name: &str) -> Option<Node> {
        if let Some(i) = self.inputs.iter().position(|n| n == name) {
            return Some(Node::Input(i));
        }
        if let Some((_, v)) = self.params.iter().find(|(n, _)| n == name) {
            return Some(Node::Num(*v));
        }
        match name {
            "pi" => Some(Node::Num(std::f64::consts::PI)),
            _ => None,
        }
    }

    fn known_names(&self) -> String {
        let mut names: Vec<&str> = self.inputs.iter().map(|s| s.as_str()).collect();
        names.extend(self.params.iter().map(|(n, _)| n.as_str()));
        names.push("pi");
        names.join(", ")
    }
}

pub fn fn1_by_name(name: &str) -> Option<Fn1> {
    Some(match name {
        "sin" => Fn1::Sin,
        "cos" => Fn1::Cos,
        "tan" => Fn1::Tan,
        "exp" => Fn1::Exp,
        "ln" => Fn1::Ln,
        "sqrt" => Fn1::Sqrt,
        "abs" => Fn1::Abs,
        _ => return None,
    })
}

pub fn fn2_by_name(name: &str) -> Option<Fn2> {
    Some(match name {
        "atan2" => Fn2::Atan2,
        "min" => Fn2::Min,
        "max" => Fn2::Max,
        "pow" => Fn2::Pow,
        _ => return None,
    })
}

/// Whether a name is taken by a function or constant (so it cannot name a variable).
pub fn is_reserved(name: &str) -> bool {
    fn1_by_name(name).is_some() || fn2_by_name(name).is_some() || name == "pi"
}

struct Parser<'a> {
    toks: Vec<Token>,
    pos: usize,
    scope: &'a Scope<'a>,
    /// Offsets of the `(` not closed yet, innermost last.
    open: Vec<usize>,
}

/// Parses one expression completely.
pub fn parse(src: &str, scope: &Scope<'_>) -> Result<Node, ExprError> {
    let mut p = Parser {
        toks: lex(src)?,
        pos: 0,
        scope,
        open: Vec::new(),
    };
    let node = p.expr()?;
    if p.peek().tok != Tok::End {
        return Err(p.error("unexpected token after a complete expression"));
    }
    Ok(node)
}

impl Parser<'_> {
    fn peek(&self) -> &Token {
        &self.toks[self.pos]
    }

    fn error(&self, message: &str) -> ExprError {
        let t = self.peek();
        ExprError {
            offset: t.offset,
            token: t.text.clone(),
            message: message.into(),
        }
    }

    fn eat(&mut self, c: char) -> bool {
        if self.peek().tok == Tok::Sym(c) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    /// The `)` of the innermost open group; missing, the error names the `(` it would close.
    fn close_group(&mut self) -> Result<(), ExprError> {
        let at = self.open.pop().unwrap_or(0);
        if self.eat(')') {
            return Ok(());
        }
        Err(self.error(&format!(
            "expected `)` to close the `(` at column {}",
            at + 1
        )))
    }

    fn expect(&mut self, c: char) -> Result<(), ExprError> {
        if self.eat(c) {
            Ok(())
        } else {
            Err(self.error(&format!("expected `{c}`")))
        }
    }

    fn expr(&mut self) -> Result<Node, ExprError> {
        let mut lhs = self.term()?;
        loop {
            let op = if self.eat('+') {
                Fn2::Add
            } else if self.eat('-') {
                Fn2::Sub
            } else {
                return Ok(lhs);
            };
            let rhs = self.term()?;
            lhs = Node::Call2(op, Box::new(lhs), Box::new(rhs));
        }
    }

    fn term(&mut self) -> Result<Node, ExprError> {
        let mut lhs = self.unary()?;
        loop {
            let op = if self.eat('*') {
                Fn2::Mul
            } else if self.eat('/') {
                Fn2::Div
            } else {
                return Ok(lhs);
            };
            let rhs = self.unary()?;
            lhs = Node::Call2(op, Box::new(lhs), Box::new(rhs));
        }
    }

    fn unary(&mut self) -> Result<Node, ExprError> {
        if self.eat('-') {
            return Ok(Node::Call1(Fn1::Neg, Box::new(self.unary()?)));
        }
        if self.eat('+') {
            return self.unary();
        }
        self.power()
    }

    fn power(&mut self) -> Result<Node, ExprError> {
        let base = self.primary()?;
        if self.eat('^') {
            let exp = self.unary()?;
            return Ok(Node::Call2(Fn2::Pow, Box::new(base), Box::new(exp)));
        }
        Ok(base)
    }

    fn primary(&mut self) -> Result<Node, ExprError> {
        let tok = self.peek().tok.clone();
        match tok {
            Tok::Num(v) => {
                self.pos += 1;
                Ok(Node::Num(v))
            }
            Tok::Sym('(') => {
                self.open.push(self.peek().offset);
                self.pos += 1;
                let e = self.expr()?;
                self.close_group()?;
                Ok(e)
            }
            Tok::Name(name) => {
                let at = self.pos;
                self.pos += 1;
                if self.peek().tok == Tok::Sym('(') {
                    return self.call(&name, at);
                }
                self.scope.lookup(&name).ok_or_else(|| {
                    let hint = if fn1_by_name(&name).is_some() || fn2_by_name(&name).is_some() {
                        format!("`{name}` is a function and needs arguments in parentheses")
                    } else if let Some(hint) = self.scope.suggest(&name) {
                        format!("unknown name `{name}`; {hint}")
                    } else {
                        format!("unknown name `{name}`; known: {}", self.scope.known_names())
                    };
                    ExprError {
                        offset: self.toks[at].offset,
                        token: name.clone(),
                        message: hint,
                    }
                })
            }
            Tok::End => Err(match self.open.last() {
                // `x*(` or `sin(`: the group is what is unfinished
                Some(&at) => self.error(&format!(
                    "expected `)` to close the `(` at column {} (and an expression inside it)",
                    at + 1
                )),
                None => self.error("expression ended early"),
            }),
            Tok::Sym(_) => Err(self.error("expected a number, a name or `(`")),
        }
    }

    fn call(&mut self, name: &str, at: usize) -> Result<Node, ExprError> {
        let offset = self.toks[at].offset;
        let name_err = |message: String| ExprError {
            offset,
            token: name.to_string(),
            message,
        };
        let arity = if fn1_by_name(name).is_some() {
            1
        } else if fn2_by_name(name).is_some() {
            2
        } else {
            const KNOWN: [&str; 11] = [
                "sin", "cos", "tan", "exp", "ln", "sqrt", "abs", "atan2", "min", "max", "pow",
            ];
            return Err(name_err(match crate::diag::did_you_mean(name, KNOWN) {
                Some(hint) => format!("unknown function `{name}`; {hint}"),
                None => format!("unknown function `{name}`; known: {}", KNOWN.join(" ")),
            }));
        };
        self.open.push(self.peek().offset);
        self.expect('(')?;
        let mut args = vec![self.expr()?];
        while self.eat(',') {
            args.push(self.expr()?);
        }
        self.close_group()?;
        if args.len() != arity {
            return Err(name_err(format!(
                "`{name}` takes {arity} argument(s), got {}",
                args.len()
            )));
        }
        let mut it = args.into_iter();
        let a = Box::new(it.next().unwrap());
        Ok(match (fn1_by_name(name), fn2_by_name(name)) {
            (Some(f), _) => Node::Call1(f, a),
            (_, Some(f)) => Node::Call2(f, a, Box::new(it.next().unwrap())),
            _ => unreachable!("arity checked above"),
        })
    }
}
