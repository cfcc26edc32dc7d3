//! Expressions compiled to a flat register program. Every instruction writes a new slot
//! (SSA), identical subexpressions are shared across all outputs (hash-consing), and
//! parameters and constants are folded at compile time, so a problem's right-hand side costs
//! about what the same formulas written by hand cost.

use std::cell::RefCell;
use std::collections::HashMap;

use super::parse::{Fn1, Fn2, Node};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Instr {
    Const(f64),
    Add(u32, u32),
    Sub(u32, u32),
    Mul(u32, u32),
    Div(u32, u32),
    Neg(u32),
    Pow(u32, u32),
    PowI(u32, i32),
    Atan2(u32, u32),
    Min(u32, u32),
    Max(u32, u32),
    Sin(u32),
    Cos(u32),
    Tan(u32),
    Exp(u32),
    Ln(u32),
    Sqrt(u32),
    Abs(u32),
}

#[derive(Hash, PartialEq, Eq)]
enum Key {
    Const(u64),
    Op1(Fn1, u32),
    Op2(Fn2, u32, u32),
    PowI(u32, i32),
}

/// A compiled set of expressions over the inputs `[t, x_0, …, x_{n−1}]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    n_inputs: usize,
    code: Vec<Instr>,
    /// slot of each output
    outputs: Vec<u32>,
}

/// Applies a one-argument function exactly as the evaluator does (used for folding too).
fn apply1(f: Fn1, a: f64) -> f64 {
    match f {
        Fn1::Neg => -a,
        Fn1::Sin => a.sin(),
        Fn1::Cos => a.cos(),
        Fn1::Tan => a.tan(),
        Fn1::Exp => a.exp(),
        Fn1::Ln => a.ln(),
        Fn1::Sqrt => a.sqrt(),
        Fn1::Abs => a.abs(),
    }
}

fn apply2(f: Fn2, a: f64, b: f64) -> f64 {
    match f {
        Fn2::Add => a + b,
        Fn2::Sub => a - b,
        Fn2::Mul => a * b,
        Fn2::Div => a / b,
        Fn2::Pow => a.powf(b),
        Fn2::Atan2 => a.atan2(b),
        Fn2::Min => a.min(b),
        Fn2::Max => a.max(b),
    }
}

struct Builder {
    n_inputs: usize,
    code: Vec<Instr>,
    seen: HashMap<Key, u32>,
}

enum Val {
    Num(f64),
    Slot(u32),
}

impl Builder {
    fn emit(&mut self, key: Key, instr: Instr) -> u32 {
        if let Some(&s) = self.seen.get(&key) {
            return s;
        }
        let slot = (self.n_inputs + self.code.len()) as u32;
        self.code.push(instr);
        self.seen.insert(key, slot);
        slot
    }

    fn slot(&mut self, v: Val) -> u32 {
        match v {
            Val::Slot(s) => s,
            Val::Num(c) => self.emit(Key::Const(c.to_bits()), Instr::Const(c)),
        }
    }

    fn node(&mut self, node: &Node) -> Val {
        match node {
            Node::Num(v) => Val::Num(*v),
            Node::Input(i) => Val::Slot(*i as u32),
            Node::Call1(f, a) => match self.node(a) {
                Val::Num(c) => Val::Num(apply1(*f, c)),
                Val::Slot(s) => {
                    let instr = match f {
                        Fn1::Neg => Instr::Neg(s),
                        Fn1::Sin => Instr::Sin(s),
                        Fn1::Cos => Instr::Cos(s),
                        Fn1::Tan => Instr::Tan(s),
                        Fn1::Exp => Instr::Exp(s),
                        Fn1::Ln => Instr::Ln(s),
                        Fn1::Sqrt => Instr::Sqrt(s),
                        Fn1::Abs => Instr::Abs(s),
                    };
                    Val::Slot(self.emit(Key::Op1(*f, s), instr))
                }
            },
            Node::Call2(f, a, b) => {
                let (a, b) = (self.node(a), self.node(b));
                if let (Val::Num(x), Val::Num(y)) = (&a, &b) {
                    return Val::Num(apply2(*f, *x, *y));
                }
                // small whole powers by multiplication: x^2 is exactly x*x
                if let (Fn2::Pow, Val::Slot(s), Val::Num(e)) = (f, &a, &b)
                    && e.fract() == 0.0
                    && e.abs() <= 64.0
                {
                    let e = *e as i32;
                    return Val::Slot(match e {
                        1 => *s,
                        2 => self.emit(Key::Op2(Fn2::Mul, *s, *s), Instr::Mul(*s, *s)),
                        _ => self.emit(Key::PowI(*s, e), Instr::PowI(*s, e)),
                    });
                }
                let (a, b) = (self.slot(a), self.slot(b));
                let instr = match f {
                    Fn2::Add => Instr::Add(a, b),
                    Fn2::Sub => Instr::Sub(a, b),
                    Fn2::Mul => Instr::Mul(a, b),
                    Fn2::Div => Instr::Div(a, b),
                    Fn2::Pow => Instr::Pow(a, b),
                    Fn2::Atan2 => Instr::Atan2(a, b),
                    Fn2::Min => Instr::Min(a, b),
                    Fn2::Max => Instr::Max(a, b),
                };
                Val::Slot(self.emit(Key::Op2(*f, a, b), instr))
            }
        }
    }
}

thread_local! {
    // registers for evaluation through `&self` (System::rhs); grown once per thread
    static REGS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl Program {
    /// Compiles expressions over `n_inputs` inputs (`Node::Input(i)`, i < n_inputs).
    pub fn compile(n_inputs: usize, exprs: &[Node]) -> Self {
        let mut b = Builder {
            n_inputs,
            code: Vec::new(),
            seen: HashMap::new(),
        };
        let outputs = exprs
            .iter()
            .map(|e| {
                let v = b.node(e);
                b.slot(v)
            })
            .collect();
        Program {
            n_inputs,
            code: b.code,
            outputs,
        }
    }

    pub fn outputs(&self) -> usize {
        self.outputs.len()
    }

    /// Number of instructions (after sharing and folding).
    pub fn len(&self) -> usize {
        self.code.len()
    }

    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }

    /// Evaluates at time t and state x (inputs `[t, x…]`) into `out`, using `regs` as
    /// scratch (grown if needed, so reuse it).
    pub fn eval_with(&self, t: f64, x: &[f64], out: &mut [f64], regs: &mut Vec<f64>) {
        debug_assert_eq!(x.len() + 1, self.n_inputs);
        let total = self.n_inputs + self.code.len();
        if regs.len() < total {
            regs.resize(total, 0.0);
        }
        let r = &mut regs[..total];
        r[0] = t;
        r[1..self.n_inputs].copy_from_slice(x);
        for (k, ins) in self.code.iter().enumerate() {
            let i = self.n_inputs + k;
            // operands always precede the slot being written
            let g = |s: u32| r[s as usize];
            let v = match *ins {
                Instr::Const(c) => c,
                Instr::Add(a, b) => g(a) + g(b),
                Instr::Sub(a, b) => g(a) - g(b),
                Instr::Mul(a, b) => g(a) * g(b),
                Instr::Div(a, b) => g(a) / g(b),
                Instr::Neg(a) => -g(a),
                Instr::Pow(a, b) => g(a).powf(g(b)),
                Instr::PowI(a, e) => g(a).powi(e),
                Instr::Atan2(a, b) => g(a).atan2(g(b)),
                Instr::Min(a, b) => g(a).min(g(b)),
                Instr::Max(a, b) => g(a).max(g(b)),
                Instr::Sin(a) => g(a).sin(),
                Instr::Cos(a) => g(a).cos(),
                Instr::Tan(a) => g(a).tan(),
                Instr::Exp(a) => g(a).exp(),
                Instr::Ln(a) => g(a).ln(),
                Instr::Sqrt(a) => g(a).sqrt(),
                Instr::Abs(a) => g(a).abs(),
            };
            r[i] = v;
        }
        for (o, &s) in out.iter_mut().zip(&self.outputs) {
            *o = r[s as usize];
        }
    }

    /// [`Program::eval_with`] on this thread's scratch registers (no allocation after the
    /// first call).
    pub fn eval(&self, t: f64, x: &[f64], out: &mut [f64]) {
        REGS.with(|regs| self.eval_with(t, x, out, &mut regs.borrow_mut()))
    }
}
